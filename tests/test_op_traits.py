"""The behaviour schema.py gives each op beside its fields: which requests carry the costmap
(COSTMAP_SENT) and what a new session is told again (RESTORED), read by both clients, the
host's journal and PROTOCOL.md from that one place."""

from __future__ import annotations

from typing import Any

import msgpack
import pytest
from nav2_pyif.client import SmootherClient, Timeouts
from nav2_pyif.client.transport import MockTransport, StaticHosts
from nav2_pyif.plan import Plan
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.supervisor import Deadlines
from nav2_pyif_codegen.cpp_codec import camel
from nav2_pyif_protocol.codec import Reply, Request, decode_request, encode_reply, encode_request
from nav2_pyif_protocol.constants import OPS_BY_PLUGIN, Op, PluginType
from nav2_pyif_protocol.schema import COSTMAP_SENT, RESTORED, SMOOTH_GRACE_S, CostmapSent

from tests.conftest import ROOT, configure_body, make_costmap

pytestmark = pytest.mark.unit

OPS_HPP = ROOT / "bridge_plugin/include/nav2_pyif_bridge/protocol/ops.hpp"


def test_the_costmap_rides_where_the_schema_gives_it_a_field() -> None:
    carrying = {op: rule for op, rule in COSTMAP_SENT.items() if rule is not CostmapSent.NEVER}
    assert carrying == {
        Op.CONFIGURE: CostmapSent.ALWAYS,
        Op.COMPUTE_VELOCITY_COMMANDS: CostmapSent.IF_CHANGED,
        Op.CREATE_PLAN: CostmapSent.IF_CHANGED,
        Op.SMOOTH: CostmapSent.IF_CHANGED,
        Op.ON_RUN: CostmapSent.IF_CHANGED,
        Op.ON_CYCLE_UPDATE: CostmapSent.IF_CHANGED,
    }
    header = OPS_HPP.read_text()
    for op, rule in COSTMAP_SENT.items():
        assert f"CostmapSent::{camel(rule.value)},  // {op.value}\n" in header, op


def test_each_plugin_type_restores_only_ops_it_sends_in_the_generated_order() -> None:
    for plugin, ops in RESTORED.items():
        assert set(ops) <= OPS_BY_PLUGIN[plugin], plugin
        assert Op.CONFIGURE not in ops and Op.ACTIVATE not in ops  # sent before, always
    header = OPS_HPP.read_text()
    pairs = [
        f"{{PluginKind::{camel(plugin.value)}, Op::{camel(op.value)}}}"
        for plugin, ops in RESTORED.items()
        for op in ops
    ]
    block = header[header.index("kRestored") :]
    assert [block.index(pair) for pair in pairs] == sorted(block.index(pair) for pair in pairs)


POSE = {"frame_id": "odom", "stamp_ns": 7, "pose": [1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]}


def _configure(plugin: PluginType) -> dict[str, Any]:
    return configure_body(plugin.value, name="plugin", node="server")


def _note(journal: Journal, op: Op, body: dict[str, Any], status: str | None = None) -> None:
    """The host's journal sees `op` with `body` answered ok (a behaviour's with `status`)."""
    payload = encode_request(Request(op, "s" * 32, 1, 1, body))
    reply = {"ok": True, "body": {"status": status} if status else {}}
    journal.note(op.value, payload, msgpack.packb(reply))


def _replayed(journal: Journal) -> list[str]:
    ((_, requests),) = journal.snapshot().values()
    return [op for op, _ in requests]


def test_the_host_journal_replays_the_restored_state_in_the_schema_order() -> None:
    journal = Journal()
    _note(journal, Op.CONFIGURE, _configure(PluginType.CONTROLLER))
    _note(journal, Op.SET_SPEED_LIMIT, {"speed_limit": 50.0, "percentage": True})
    _note(journal, Op.SET_PLAN, {"path": {"frame_id": "map", "stamp_ns": 0, "poses": b""}})
    _note(journal, Op.ACTIVATE, {})
    restored = [op.value for op in RESTORED[PluginType.CONTROLLER]]
    assert _replayed(journal) == ["configure", "activate", *restored]
    ((_, requests),) = journal.snapshot().values()
    assert decode_request(requests[2][1]).body["path"]["frame_id"] == "map"


def test_a_behaviour_is_restored_only_while_its_action_runs() -> None:
    journal = Journal()
    _note(journal, Op.CONFIGURE, _configure(PluginType.BEHAVIOR))
    run = {"action": "nav2_msgs/action/BackUp", "command": {}, "pose": POSE}
    _note(journal, Op.ON_RUN, run, status="succeeded")
    assert _replayed(journal) == ["configure", "on_run"]
    _note(journal, Op.ON_ACTION_COMPLETION, {"status": "succeeded", "elapsed": 1.0})
    assert _replayed(journal) == ["configure"]
    _note(journal, Op.ON_RUN, run, status="failed")  # refused: no action under way
    assert _replayed(journal) == ["configure"]


def test_smooth_waits_its_max_time_and_a_grace_or_the_plan_timeout_when_longer() -> None:
    """As the C++ session (units_test.cpp: SmootherSessionTest.WaitsMaxTimeAndAGrace...)."""
    waits: list[float] = []

    def host(key: str, host: str | None, payload: bytes, timeout: float) -> bytes:
        request = decode_request(payload)
        waits.append(timeout)
        body: dict[str, Any] = {"declared": {}}
        if request.op is Op.SMOOTH:
            body = {"path": request.body["path"], "was_completed": True}
        return encode_reply(Reply(seq=request.seq, ok=True, host="h", body=body), request.op)

    hosts = StaticHosts()
    hosts.set(["h"])
    timeouts = Timeouts(call=0.04, lifecycle=1.5, configure=10.0, plan=2.0)
    client = SmootherClient(
        MockTransport(host, hosts), "nav2_pyif/t/smoother", make_costmap(), timeouts=timeouts
    )
    client.configure()
    path = Plan([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]] * 3, "odom", 1)
    client.smooth(path, 5.0)
    client.smooth(path, 0.5)
    assert waits[1:] == [5.0 + SMOOTH_GRACE_S, 2.0]
    assert client.timeouts.plan == 2.0


def test_the_host_lets_a_smoother_use_its_max_time_and_the_grace() -> None:
    """The host's side of the same wait: its plan deadline would otherwise answer a smoother
    given a longer max_time Unavailable before the plugin stops waiting."""
    deadlines = Deadlines(plan=30.0)
    path = {"frame_id": "map", "stamp_ns": 0, "poses": b""}

    def smooth(max_time: float) -> bytes:
        return encode_request(
            Request(Op.SMOOTH, "s" * 32, 1, 1, {"path": path, "max_time": max_time})
        )

    assert deadlines.of("smooth", smooth(40.0)) == 40.0 + SMOOTH_GRACE_S
    assert deadlines.of("smooth", smooth(0.5)) == 30.0
    assert deadlines.of("smooth", b"\xc1 not msgpack") == 30.0
    assert deadlines.of("create_plan", smooth(40.0)) == 30.0
