"""nav2-pyif replay's comparison of a replayed reply with the recorded one, on replies the
protocol's own codec encodes: a command's dv and dw, a plan's pose distances both ways, errors,
and a digest that ignores who answered and how long it took."""

from __future__ import annotations

import numpy as np
import pytest
from nav2_pyif.replay.compare import compare, plan_distance
from nav2_pyif_protocol.arrays import pack_poses, poses_from_xy_yaw
from nav2_pyif_protocol.codec import ErrorInfo, Reply, encode_reply
from nav2_pyif_protocol.constants import Op

pytestmark = pytest.mark.unit


def command(vx: float, wz: float, host: str = "a", compute_ns: int = 1000) -> bytes:
    body = {"cmd_vel": {"frame_id": "base_link", "stamp_ns": 5, "twist": [vx, 0, 0, 0, 0, wz]}}
    reply = Reply(seq=3, ok=True, host=host, body=body, compute_ns=compute_ns)
    return encode_reply(reply, Op.COMPUTE_VELOCITY_COMMANDS)


def plan(xy: np.ndarray) -> bytes:
    path = {"frame_id": "map", "stamp_ns": 0, "poses": pack_poses(poses_from_xy_yaw(xy))}
    return encode_reply(Reply(seq=4, ok=True, host="a", body={"path": path}), Op.CREATE_PLAN)


def test_a_command_differs_by_dv_and_dw_and_not_by_host_or_time() -> None:
    same = compare(
        0, "k", "compute_velocity_commands", 0.0, command(0.5, 0.1), command(0.5, 0.1, "b", 9000)
    )
    assert same.identical and (same.dv, same.dw) == (0.0, 0.0)
    assert (same.recorded_compute_ms, same.compute_ms) == (0.001, 0.009)
    slower = compare(
        1, "k", "compute_velocity_commands", 0.1, command(0.5, 0.1), command(0.25, 0.3)
    )
    assert not slower.identical and slower.output != same.output
    assert slower.dv == pytest.approx(-0.25) and slower.dw == pytest.approx(0.2)


def test_an_error_reply_is_reported_with_its_type_and_message() -> None:
    error = ErrorInfo("NoValidControl", "blocked", "", "")
    failed = encode_reply(
        Reply(seq=3, ok=False, host="b", error=error), Op.COMPUTE_VELOCITY_COMMANDS
    )
    diff = compare(0, "k", "compute_velocity_commands", 0.0, command(0.5, 0.0), failed)
    assert diff.error == "[NoValidControl] blocked" and diff.recorded_error == ""
    assert diff.dv is None and not diff.identical
    missing = compare(0, "k", "compute_velocity_commands", 0.0, None, command(0.5, 0.0))
    assert missing.recorded_error == "no recorded reply" and not missing.identical


def test_plans_differ_by_the_distance_of_their_poses_both_ways() -> None:
    line = np.column_stack([np.linspace(0, 2, 21), np.zeros(21)])
    shifted = line + np.array([0.0, 0.1])
    diff = compare(0, "k", "create_plan", 0.0, plan(line), plan(shifted))
    assert diff.plan_max == pytest.approx(0.1) and diff.plan_mean == pytest.approx(0.1)
    # a plan that stops halfway: its poses lie on the other, whose last ten are 0.1 to 1 m
    # from it; 32 distances in all
    assert plan_distance(line[:11], line) == pytest.approx((1.0, 5.5 / 32))
    assert plan_distance(line, line) == (0.0, 0.0)
    assert plan_distance(line[:0], line) is None
    assert compare(0, "k", "create_plan", 0.0, plan(line), plan(line)).identical
