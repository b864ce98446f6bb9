"""Shared test vectors: the contract both codecs are tested against.

Each vector is ``<name>.msgpack`` (the exact bytes) and ``<name>.json`` (the decoded msgpack
object tree). ``index.json`` lists them with their kind (request / reply) and op. In the JSON
form, byte strings are ``{"$bin": "<hex>"}`` (or ``{"$bin_len": n, "$bin_crc32": c}`` above
4 KiB), non-finite floats are ``{"$float": "nan" | "inf" | "-inf"}``, and floats are always
written with a decimal point or exponent, ints never.

    nav2-pyif-vectors --check protocol/vectors    # exit 1 if the files differ from the code
    nav2-pyif-vectors --write protocol/vectors    # regenerate after a deliberate change
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import zlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import msgpack
import numpy as np
from nav2_pyif_protocol.arrays import pack_poses, pack_xy
from nav2_pyif_protocol.codec import ErrorInfo, Reply, Request, encode_reply, encode_request
from nav2_pyif_protocol.constants import PROTOCOL_VERSION, ErrorType, Op

from nav2_pyif_codegen.key_vectors import rendered_keys
from nav2_pyif_codegen.transcripts import rendered_transcripts

INLINE_BIN_LIMIT = 4096
SID = "3f2a9c7e5b1d4e8f9a0b1c2d3e4f5a6b"
HOST = "host-a-4242-01"

# Real CDR (rclpy.serialization.serialize_message): a LaserScan of 3 beams in frame "laser",
# stamp 12 s, ranges [1.0, 2.5, inf]; a PointStamped (1.5, -0.5, 0) in "map". The codec
# carries them as opaque bytes; the host tests deserialise them.
SCAN_CDR = bytes.fromhex(
    "000100000c00000000000000060000006c617365720000000000c0bf0000c03f0000c03f00000000000000"
    "00cdcccc3d00000041030000000000803f000020400000807f00000000"
)
POINT_CDR = bytes.fromhex(
    "000100000000000000000000040000006d617000000000000000f83f000000000000e0bf0000000000000000"
)


@dataclass(frozen=True)
class Vector:
    name: str
    kind: str  # "request" | "reply"
    op: Op
    data: bytes
    description: str


def costmap(size_x: int, size_y: int, version: int, frame: str = "map") -> dict[str, Any]:
    """A deterministic costmap: free, a lethal border, an inflated ramp and unknown cells."""
    mx, my = np.meshgrid(np.arange(size_x), np.arange(size_y))
    grid = ((mx * 7 + my * 13) % 256).astype(np.uint8)
    grid[0, :] = 254
    grid[:, 0] = 253
    grid[-1, -1] = 255
    return {
        "version": version,
        "frame_id": frame,
        "size_x": size_x,
        "size_y": size_y,
        "resolution": 0.05,
        "origin_x": -10.0,
        "origin_y": -7.5,
        "data": grid.tobytes(),
        "footprint": pack_xy([[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]),
        "robot_radius": 0.0,
    }


# Vector values come from Python's math (correctly rounded libm), never NumPy's SIMD
# kernels, so regenerating the vectors gives the same bytes on every CPU.
def _pose7(x: float, y: float, yaw: float) -> list[float]:
    return [x, y, 0.0, 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)]


def pose(x: float, y: float, yaw: float, frame: str = "map") -> dict[str, Any]:
    return {"frame_id": frame, "stamp_ns": 1_700_000_000_123_456_789, "pose": _pose7(x, y, yaw)}


def path(n: int, frame: str = "map") -> dict[str, Any]:
    ts = [i / (n - 1) if n > 1 else 0.0 for i in range(n)]
    rows = [_pose7(t * 10.0, math.sin(t * 3.0), 0.25) for t in ts]
    return {"frame_id": frame, "stamp_ns": 5, "poses": pack_poses(np.array(rows).reshape(-1, 7))}


def _requests() -> Iterator[tuple[str, Request, str]]:
    def req(op: Op, body: dict[str, Any], seq: int = 7, epoch: int = 1) -> Request:
        return Request(op=op, sid=SID, epoch=epoch, seq=seq, body=body)

    configure = {
        "plugin_type": "controller",
        "name": "FollowPath",
        "node": "controller_server",
        "params": {
            "max_vel_x": 0.5,
            "lookahead_dist": 0.6,
            "use_rotate": True,
            "horizon_steps": 30,
            "mode": "fast",
            "weights": [1.0, 2.5],
            "tags": ["a", "b"],
        },
        "global_frame": "odom",
        "robot_base_frame": "base_link",
        "costmap": costmap(4, 3, 1, "odom"),
    }
    yield "configure_controller", req(Op.CONFIGURE, configure, seq=0), "controller configure"
    told = {"controller_frequency": 20.0, "inflation_radius": 0.55, "cost_scaling_factor": 3.0}
    yield (
        "configure_controller_nav2_params",
        req(Op.CONFIGURE, dict(configure, nav2_params=told), seq=0),
        "controller configure with Nav2's parameters beyond the plugin's (optional)",
    )
    planner_configure = dict(
        configure,
        plugin_type="global_planner",
        name="GridBased",
        node="planner_server",
        params={},
        global_frame="map",
        costmap=costmap(1, 1, 9),
    )
    yield "configure_planner_1x1", req(Op.CONFIGURE, planner_configure, seq=0), "1x1 costmap"
    for op in (Op.ACTIVATE, Op.DEACTIVATE, Op.CLEANUP, Op.CANCEL, Op.RESET):
        yield f"{op.value}_request", req(op, {}), f"{op.value}: empty body"
    yield "set_parameters_request", req(Op.SET_PARAMETERS, {"params": {"max_vel_x": 0.25}}), ""
    yield "set_plan_request", req(Op.SET_PLAN, {"path": path(5)}), "5-pose path"
    yield "set_plan_empty", req(Op.SET_PLAN, {"path": path(0)}), "empty path: zero-length bin"
    yield "set_plan_1000", req(Op.SET_PLAN, {"path": path(1000)}), "1000-pose path"
    yield (
        "set_plan_with_goal",
        req(Op.SET_PLAN, {"path": path(3, "odom"), "goal": pose(5.0, -2.0, 3.0, "odom")}),
        "Lyrical: the plan and Nav2's global goal, re-sent to a new session",
    )
    cvc = {
        "pose": pose(1.0, 2.0, 0.5, "odom"),
        "velocity": [0.3, 0.0, 0.0, 0.0, 0.0, 0.1],
        "goal_checker": {
            "xy_goal_tolerance": 0.25,
            "yaw_goal_tolerance": 0.25,
            "trans_stopped_velocity": 0.25,
            "rot_stopped_velocity": 0.25,
        },
    }
    yield (
        "compute_velocity_commands_request",
        req(Op.COMPUTE_VELOCITY_COMMANDS, cvc, seq=1234),
        ("costmap unchanged: no costmap field"),
    )
    minimal = {"pose": cvc["pose"], "velocity": cvc["velocity"]}
    yield (
        "compute_velocity_commands_no_goal_checker",
        req(Op.COMPUTE_VELOCITY_COMMANDS, minimal, seq=2**32),
        "no goal checker; seq 2^32 (uint64)",
    )
    with_map = dict(cvc, costmap=costmap(400, 400, 17, "odom"))
    yield (
        "compute_velocity_commands_costmap_400",
        req(Op.COMPUTE_VELOCITY_COMMANDS, with_map, seq=1235),
        "costmap changed: 400x400 attached",
    )
    nan_velocity = dict(minimal, velocity=[math.nan, 0.0, math.inf, -math.inf, -0.0, 0.0])
    yield (
        "compute_velocity_commands_nan_velocity",
        req(Op.COMPUTE_VELOCITY_COMMANDS, nan_velocity, epoch=3),
        "non-finite and negative-zero floats survive the codec",
    )
    unicode_pose = pose(0.0, 0.0, 0.0, "карта/地図/ø")
    yield (
        "compute_velocity_commands_unicode_frame",
        req(Op.COMPUTE_VELOCITY_COMMANDS, dict(minimal, pose=unicode_pose)),
        "non-ASCII frame id",
    )
    with_inputs = dict(
        minimal,
        inputs=[
            {
                "name": "scan",
                "type": "sensor_msgs/msg/LaserScan",
                "stamp_ns": 12_000_000_000,
                "cdr": SCAN_CDR,
            }
        ],
        debug_wanted=["local_plan", "lookahead_point"],
    )
    yield (
        "compute_velocity_commands_inputs",
        req(Op.COMPUTE_VELOCITY_COMMANDS, with_inputs, seq=1236),
        "a new scan (real CDR) and two debug outputs someone subscribes to",
    )
    with_plan = dict(
        cvc,
        goal_checker={
            "xy_goal_tolerance": 0.25,
            "yaw_goal_tolerance": 0.25,
            "trans_stopped_velocity": 0.25,
            "rot_stopped_velocity": 0.25,
            "path_length_tolerance": 1.0,
        },
        plan=path(4, "odom"),
        goal=pose(5.0, -2.0, 3.0, "odom"),
    )
    yield (
        "compute_velocity_commands_transformed_plan",
        req(Op.COMPUTE_VELOCITY_COMMANDS, with_plan, seq=1237),
        "Lyrical: the plan Nav2 transformed and the global goal, both changed since last sent",
    )
    yield (
        "set_speed_limit_absolute",
        req(Op.SET_SPEED_LIMIT, {"speed_limit": 0.35, "percentage": False}),
        "",
    )
    yield (
        "set_speed_limit_percentage",
        req(Op.SET_SPEED_LIMIT, {"speed_limit": 50.0, "percentage": True}),
        "",
    )
    plan_body = {"start": pose(0.0, 0.0, 0.0), "goal": pose(5.0, -2.0, 3.14159)}
    yield "create_plan_request", req(Op.CREATE_PLAN, plan_body, seq=3), ""
    big = dict(plan_body, costmap=costmap(1000, 1000, 2))
    yield "create_plan_costmap_1000", req(Op.CREATE_PLAN, big, seq=4), "1000x1000 costmap"
    yield (
        "create_plan_viapoints",
        req(Op.CREATE_PLAN, dict(plan_body, viapoints=path(2)), seq=6),
        "Lyrical: two viapoints",
    )
    yield "cancel_plan_request", req(Op.CANCEL_PLAN, {"target_seq": 3}, seq=5), ""
    smoother_configure = dict(
        planner_configure,
        plugin_type="smoother",
        name="simple_smoother",
        node="smoother_server",
        params={"tolerance": 1e-10, "max_its": 1000, "do_refinement": True},
        costmap=costmap(6, 5, 2),
    )
    yield "configure_smoother", req(Op.CONFIGURE, smoother_configure, seq=0), "smoother"
    checker_configure = dict(
        configure,
        plugin_type="progress_checker",
        name="progress_checker",
        params={"required_movement_radius": 0.5, "movement_time_allowance": 10.0},
        costmap={**costmap(1, 1, 0, "odom"), "size_x": 0, "size_y": 0, "data": b""},
    )
    yield (
        "configure_progress_checker",
        req(Op.CONFIGURE, checker_configure, seq=0),
        "a plugin without a costmap: 0 x 0",
    )
    smooth = {"path": path(7), "max_time": 0.1}
    yield "smooth_request", req(Op.SMOOTH, smooth, seq=11), "costmap unchanged"
    yield (
        "smooth_costmap",
        req(Op.SMOOTH, dict(smooth, costmap=costmap(20, 10, 3)), seq=12),
        "costmap changed: attached",
    )
    reached = {
        "pose": _pose7(1.0, 2.0, 0.5),
        "goal": _pose7(1.1, 2.0, 0.4),
        "velocity": [0.01, 0.0, 0.0, 0.0, 0.0, -0.02],
    }
    yield "is_goal_reached_request", req(Op.IS_GOAL_REACHED, reached, seq=13), ""
    yield (
        "is_goal_xy_reached_request",
        req(Op.IS_GOAL_REACHED, dict(reached, xy_only=True), seq=17),
        "Lyrical's isGoalXYReached",
    )
    check = encode_request(req(Op.CHECK, {"pose": pose(1.0, 2.0, 0.5, "odom")}, seq=90))
    compute = encode_request(req(Op.COMPUTE_VELOCITY_COMMANDS, minimal, seq=91))
    carrying = dict(
        reached,
        carry=[
            {"key": "nav2_pyif/robot1/progress_checker", "payload": check},
            {"key": "nav2_pyif/robot1/FollowPath", "payload": compute},
        ],
    )
    yield (
        "is_goal_reached_carrying_the_cycle",
        req(Op.IS_GOAL_REACHED, carrying, seq=16),
        "the progress check and the controller's call carried along (encoded requests)",
    )
    goal_check = encode_request(req(Op.IS_GOAL_REACHED, reached, seq=93))
    yield (
        "compute_velocity_commands_carrying_the_goal_check",
        req(
            Op.COMPUTE_VELOCITY_COMMANDS,
            dict(minimal, carry=[{"key": "nav2_pyif/robot1/goal_checker", "payload": goal_check}]),
            seq=94,
        ),
        "the goal check last (Humble's order): the command carries it (encoded request)",
    )
    yield "get_tolerances_request", req(Op.GET_TOLERANCES, {}, seq=14), "empty body"
    yield "check_request", req(Op.CHECK, {"pose": pose(3.0, -1.0, 1.0, "odom")}, seq=15), ""
    yield (
        "check_carrying_the_command",
        req(
            Op.CHECK,
            {
                "pose": pose(1.0, 2.0, 0.5, "odom"),
                "carry": [{"key": "nav2_pyif/robot1/FollowPath", "payload": compute}],
            },
            seq=92,
        ),
        "TF moved on since the goal check: the check carries the command (encoded request)",
    )
    bounds = {"robot_x": 1.5, "robot_y": -0.5, "robot_yaw": 0.25}
    bounds.update(min_x=1e30, min_y=1e30, max_x=-1e30, max_y=-1e30)
    yield "update_bounds_request", req(Op.UPDATE_BOUNDS, bounds, seq=17), "no bounds yet"
    window: dict[str, Any] = {"min_i": 10, "min_j": 20, "max_i": 14, "max_j": 23}
    window.update(origin_x=-10.0, origin_y=-7.5, resolution=0.05)
    yield "update_costs_request", req(Op.UPDATE_COSTS, window, seq=18), "a 4 x 3 window"
    grid = {"size_x": 400, "size_y": 400, "resolution": 0.05, "origin_x": -10.0, "origin_y": -10.0}
    yield "match_size_request", req(Op.MATCH_SIZE, grid, seq=19), ""
    behavior_configure = dict(
        configure,
        plugin_type="behavior",
        name="backup",
        node="behavior_server",
        params={"free_threshold": 0.5, "max_turn": 1.57},
        costmap=costmap(8, 6, 1, "odom"),
    )
    yield "configure_behavior", req(Op.CONFIGURE, behavior_configure, seq=0), "a behaviour"
    backup = {
        "target_x": -0.3,
        "target_y": 0.0,
        "target_z": 0.0,
        "speed": 0.15,
        "time_allowance": 10.0,
        "disable_collision_checks": False,
    }
    run = {
        "action": "nav2_msgs/action/BackUp",
        "command": backup,
        "pose": pose(1.0, 2.0, 0.5, "odom"),
        "costmap": costmap(8, 6, 2, "odom"),
    }
    yield "on_run_request", req(Op.ON_RUN, run, seq=20), "BackUp's goal, costmap changed"
    cycle = {"pose": pose(0.9, 1.95, 0.5, "odom"), "elapsed": 0.1}
    yield "on_cycle_update_request", req(Op.ON_CYCLE_UPDATE, cycle, seq=21), ""
    ended = {"status": "succeeded", "elapsed": 2.5}
    yield "on_action_completion_request", req(Op.ON_ACTION_COMPLETION, ended, seq=22), ""
    handler_configure = dict(
        configure,
        plugin_type="path_handler",
        name="path_handler",
        params={"prune_distance": 2.0},
        costmap=costmap(8, 6, 1, "odom"),
    )
    yield (
        "configure_path_handler",
        req(Op.CONFIGURE, handler_configure, seq=0),
        "Lyrical's nav2_core::PathHandler",
    )
    segment = {"pose": pose(1.0, 2.0, 0.5, "odom")}
    yield "find_plan_segment_request", req(Op.FIND_PLAN_SEGMENT, segment, seq=23), ""
    check_carrying = dict(
        segment,
        carry=[
            {
                "key": "nav2_pyif/robot1/path_handler",
                "payload": encode_request(req(Op.FIND_PLAN_SEGMENT, segment, seq=24)),
            }
        ],
    )
    yield (
        "check_carrying_the_plan_segment",
        req(Op.CHECK, check_carrying, seq=25),
        "Lyrical's order: the path handler's call rides with the progress check",
    )


def _replies() -> Iterator[tuple[str, Op, Reply, str]]:
    def ok(op: Op, body: dict[str, Any], seq: int = 7, compute_ns: int = 12_345) -> Reply:
        return Reply(seq=seq, ok=True, host=HOST, body=body, compute_ns=compute_ns)

    yield (
        "configure_reply",
        Op.CONFIGURE,
        ok(Op.CONFIGURE, {"declared": {"max_vel_x": 0.5, "k_rep": 2}}, seq=0),
        "declared parameters",
    )
    yield (
        "configure_reply_planner_undeclared",
        Op.CONFIGURE,
        ok(
            Op.CONFIGURE,
            {
                "declared": {"max_vel_x": 0.5},
                "planner": "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
                "undeclared": {
                    "max_vel": "'max_vel' is not declared (declared: max_vel_x)",
                    "lookahed": "'lookahed' is not declared (declared: max_vel_x)",
                },
            },
            seq=0,
        ),
        "the optional planner label and parameters the planner ignores",
    )
    for op in (Op.ACTIVATE, Op.DEACTIVATE, Op.CLEANUP, Op.SET_PLAN, Op.RESET, Op.SET_SPEED_LIMIT):
        yield f"{op.value}_reply", op, ok(op, {}, compute_ns=0), "empty body"
    yield (
        "set_parameters_reply",
        Op.SET_PARAMETERS,
        ok(Op.SET_PARAMETERS, {"rejected": {"max_vel_x": "expected float, got str"}}),
        "",
    )
    cmd = {"frame_id": "base_link", "stamp_ns": 42, "twist": [0.4, 0.0, 0.0, 0.0, 0.0, -0.2]}
    yield (
        "compute_velocity_commands_reply",
        Op.COMPUTE_VELOCITY_COMMANDS,
        ok(Op.COMPUTE_VELOCITY_COMMANDS, {"cmd_vel": cmd}, seq=1234),
        "",
    )
    debug = [
        {"name": "lookahead_point", "type": "geometry_msgs/msg/PointStamped", "cdr": POINT_CDR}
    ]
    yield (
        "compute_velocity_commands_reply_debug",
        Op.COMPUTE_VELOCITY_COMMANDS,
        ok(Op.COMPUTE_VELOCITY_COMMANDS, {"cmd_vel": cmd, "debug": debug}, seq=1236),
        "a debug output (real CDR) with the command",
    )
    yield (
        "configure_reply_debug_outputs",
        Op.CONFIGURE,
        ok(
            Op.CONFIGURE,
            {
                "declared": {},
                "debug_outputs": {
                    "local_plan": "nav_msgs/msg/Path",
                    "lookahead_point": "geometry_msgs/msg/PointStamped",
                },
            },
            seq=0,
        ),
        "the debug outputs a planner may return",
    )
    yield "cancel_reply", Op.CANCEL, ok(Op.CANCEL, {"cancelled": True}), ""
    yield "create_plan_reply", Op.CREATE_PLAN, ok(Op.CREATE_PLAN, {"path": path(50)}, seq=3), ""
    yield "create_plan_reply_empty", Op.CREATE_PLAN, ok(Op.CREATE_PLAN, {"path": path(0)}), ""
    yield "cancel_plan_reply", Op.CANCEL_PLAN, ok(Op.CANCEL_PLAN, {"accepted": True}, seq=5), ""
    smoothed = {"path": path(7), "was_completed": True}
    yield "smooth_reply", Op.SMOOTH, ok(Op.SMOOTH, smoothed, seq=11), ""
    yield (
        "smooth_reply_incomplete",
        Op.SMOOTH,
        ok(Op.SMOOTH, {"path": path(0), "was_completed": False}, seq=12),
        "stopped at max_time; empty path",
    )
    yield (
        "is_goal_reached_reply",
        Op.IS_GOAL_REACHED,
        ok(Op.IS_GOAL_REACHED, {"reached": True}, seq=13),
        "",
    )
    command = {
        "key": "nav2_pyif/robot1/FollowPath",
        "payload": encode_reply(
            ok(Op.COMPUTE_VELOCITY_COMMANDS, {"cmd_vel": cmd}, seq=91),
            Op.COMPUTE_VELOCITY_COMMANDS,
        ),
    }
    progress = encode_reply(ok(Op.CHECK, {"making_progress": True}, seq=90), Op.CHECK)
    carried = {
        "reached": False,
        "carried": [{"key": "nav2_pyif/robot1/progress_checker", "payload": progress}, command],
    }
    yield (
        "is_goal_reached_reply_carrying_the_cycle",
        Op.IS_GOAL_REACHED,
        ok(Op.IS_GOAL_REACHED, carried, seq=16),
        "not reached: the carried replies (encoded)",
    )
    grown = {"min_x": 1.0, "min_y": -1.0, "max_x": 2.5, "max_y": 0.75}
    yield "update_bounds_reply", Op.UPDATE_BOUNDS, ok(Op.UPDATE_BOUNDS, grown, seq=17), ""
    costs = {"width": 4, "height": 3, "costs": bytes([0, 254, 254, 255] * 3), "combine": "max"}
    yield "update_costs_reply", Op.UPDATE_COSTS, ok(Op.UPDATE_COSTS, costs, seq=18), ""
    yield "match_size_reply", Op.MATCH_SIZE, ok(Op.MATCH_SIZE, {}, seq=19), "empty body"
    started = {"status": "succeeded", "failure": ""}
    yield "on_run_reply", Op.ON_RUN, ok(Op.ON_RUN, started, seq=20), "start the cycle"
    step = {
        "status": "running",
        "failure": "",
        "cmd_vel": {"frame_id": "base_link", "stamp_ns": 42, "twist": [-0.15] + [0.0] * 5},
        "feedback": {"distance_traveled": 0.11},
    }
    yield (
        "on_cycle_update_reply",
        Op.ON_CYCLE_UPDATE,
        ok(Op.ON_CYCLE_UPDATE, step, seq=21),
        "running: a command and feedback",
    )
    yield (
        "on_cycle_update_reply_collision",
        Op.ON_CYCLE_UPDATE,
        ok(Op.ON_CYCLE_UPDATE, {"status": "failed", "failure": "collision_ahead"}, seq=21),
        "failed, no command: the plugin stops the robot",
    )
    yield (
        "on_action_completion_reply",
        Op.ON_ACTION_COMPLETION,
        ok(Op.ON_ACTION_COMPLETION, {}, seq=22),
        "empty body",
    )
    tolerances = {
        "available": True,
        "pose_tolerance": [0.25, 0.25, 0.0, 0.0, 0.0, math.sin(0.125), math.cos(0.125)],
        "velocity_tolerance": [0.25, 0.25, 0.0, 0.0, 0.0, 0.25],
    }
    yield (
        "get_tolerances_reply",
        Op.GET_TOLERANCES,
        ok(Op.GET_TOLERANCES, tolerances, seq=14),
        "",
    )
    yield (
        "get_tolerances_path_length_reply",
        Op.GET_TOLERANCES,
        ok(Op.GET_TOLERANCES, dict(tolerances, path_length_tolerance=1.0), seq=18),
        "Lyrical's path length tolerance",
    )
    yield (
        "check_reply",
        Op.CHECK,
        ok(Op.CHECK, {"making_progress": False}, seq=15),
        "failed to make progress",
    )
    yield (
        "check_reply_carrying_the_command",
        Op.CHECK,
        ok(Op.CHECK, {"making_progress": True, "carried": [command]}, seq=92),
        "making progress: the carried command's reply (encoded)",
    )
    yield (
        "find_plan_segment_reply",
        Op.FIND_PLAN_SEGMENT,
        ok(Op.FIND_PLAN_SEGMENT, {"start": 3, "end": 41}, seq=23),
        "the poses 3 to 40 of the plan",
    )
    errors = [
        (
            "error_no_valid_control",
            Op.COMPUTE_VELOCITY_COMMANDS,
            ErrorType.NO_VALID_CONTROL,
            "compute_velocity_commands returned a non-finite twist: linear.x=nan",
            'Traceback (most recent call last):\n  File "apf.py", line 3\nValueError: x\n',
            "",
        ),
        (
            "error_python_exception",
            Op.COMPUTE_VELOCITY_COMMANDS,
            ErrorType.CONTROLLER_EXCEPTION,
            "ZeroDivisionError: division by zero",
            'Traceback (most recent call last):\n  File "c.py", line 9, in f\n'
            "ZeroDivisionError: division by zero\n",
            "builtins.ZeroDivisionError",
        ),
        (
            "error_session_unknown",
            Op.SET_PLAN,
            ErrorType.SESSION_UNKNOWN,
            "session 3f2a... epoch 2 is not known to this host",
            "",
            "",
        ),
        (
            "error_version_mismatch",
            Op.ACTIVATE,
            ErrorType.VERSION_MISMATCH,
            f"request speaks protocol version {PROTOCOL_VERSION + 1}; this host speaks "
            f"{PROTOCOL_VERSION}",
            "",
            "",
        ),
        (
            "error_no_path_unicode",
            Op.CREATE_PLAN,
            ErrorType.NO_VALID_PATH_COULD_BE_FOUND,
            "kein Pfad gefunden → 目標に到達できません",
            "",
            "nav2_pyif.exceptions.X",
        ),
        (
            "error_smoothed_path_in_collision",
            Op.SMOOTH,
            ErrorType.SMOOTHED_PATH_IN_COLLISION,
            "smoothed pose 3 is lethal",
            "",
            "nav2_pyif.exceptions.SmoothedPathInCollision",
        ),
        (
            "error_unavailable",
            Op.CREATE_PLAN,
            ErrorType.UNAVAILABLE,
            "planner worker is restarting",
            "",
            "",
        ),
    ]
    for name, op, etype, message, tb, pytype in errors:
        yield (
            name,
            op,
            Reply(seq=9, ok=False, host=HOST, error=ErrorInfo(etype.value, message, tb, pytype)),
            etype.value,
        )


def build_vectors() -> list[Vector]:
    vectors = [Vector(n, "request", r.op, encode_request(r), d) for n, r, d in _requests()]
    # A request from a newer protocol version; hosts must answer VersionMismatch.
    future = Request(op=Op.ACTIVATE, sid=SID, epoch=1, seq=1, v=PROTOCOL_VERSION + 1)
    vectors.append(
        Vector(
            "activate_newer_version",
            "request",
            Op.ACTIVATE,
            encode_request(future),
            f"protocol version {PROTOCOL_VERSION + 1}: VersionMismatch",
        )
    )
    vectors += [Vector(n, "reply", op, encode_reply(r, op), d) for n, op, r, d in _replies()]
    return vectors


# --- JSON form of a decoded msgpack tree --------------------------------------------------


def to_json_tree(value: Any) -> Any:
    if isinstance(value, bytes):
        if len(value) <= INLINE_BIN_LIMIT:
            return {"$bin": value.hex()}
        return {"$bin_len": len(value), "$bin_crc32": zlib.crc32(value)}
    if isinstance(value, float) and not math.isfinite(value):
        return {"$float": "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")}
    if isinstance(value, dict):
        return {k: to_json_tree(v) for k, v in value.items()}
    if isinstance(value, list):
        return [to_json_tree(v) for v in value]
    return value


def expected_json(data: bytes) -> str:
    tree = msgpack.unpackb(data, raw=False)
    return json.dumps(to_json_tree(tree), indent=1, ensure_ascii=False) + "\n"


def index_json(vectors: list[Vector]) -> str:
    entries = [
        {"name": v.name, "kind": v.kind, "op": v.op.value, "description": v.description}
        for v in vectors
    ]
    return json.dumps({"protocol_version": 1, "vectors": entries}, indent=1) + "\n"


def rendered_files(vectors: list[Vector]) -> dict[str, bytes]:
    """Relative path -> content: the vectors, the session transcripts in transcripts/ and the
    key rules in keys.json."""
    files: dict[str, bytes] = {"index.json": index_json(vectors).encode()}
    for v in vectors:
        files[f"{v.name}.msgpack"] = v.data
        files[f"{v.name}.json"] = expected_json(v.data).encode()
    files.update(rendered_transcripts())
    files.update(rendered_keys())
    return files


def _on_disk(directory: Path) -> list[str]:
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*") if p.is_file())


def _check(directory: Path, files: dict[str, bytes], report: Callable[[str], None]) -> int:
    problems = 0
    for name, content in files.items():
        on_disk = directory / name
        if not on_disk.exists() or on_disk.read_bytes() != content:
            report(f"differs: {on_disk}")
            problems += 1
    known = set(files)
    for stray in (name for name in _on_disk(directory) if name not in known):
        report(f"not produced by the code: {directory / stray}")
        problems += 1
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="nav2-pyif-vectors", description="Write or check the shared protocol test vectors."
    )
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--write", type=Path, metavar="DIR", help="regenerate the vectors in DIR")
    group.add_argument("--check", type=Path, metavar="DIR", help="fail if DIR is out of date")
    args = parser.parse_args(argv)
    files = rendered_files(build_vectors())
    if args.write:
        for stale in _on_disk(args.write) if args.write.exists() else []:
            if stale not in files:
                (args.write / stale).unlink()
        for name, content in files.items():
            (args.write / name).parent.mkdir(parents=True, exist_ok=True)
            (args.write / name).write_bytes(content)
        print(f"wrote {len(files)} files to {args.write}")
        return 0
    problems = _check(args.check, files, lambda line: print(line, file=sys.stderr))
    print(f"{len(files) - problems} of {len(files)} vector files match")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
