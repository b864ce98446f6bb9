"""Session transcripts: the plugin rules as sequences of Nav2 calls, the exact requests each
makes a client send (with the timeout it waits) and the fake host's replies. Both clients
replay them (tests/test_transcripts.py, bridge_plugin/test/client/transcripts_test.cpp), as
every rmw passes rmw_implementation's one conformance suite. Format: PROTOCOL.md section 18.

Written here by hand, step by step: a transcript is the rule, not a recording of a client.
The one thing taken from elsewhere is each op's timeout class (schema.OP_TIMEOUT), so a
client waiting with another class than the table fails its replay.
"""

from __future__ import annotations

import json
import math
import struct
from dataclasses import dataclass, field
from typing import Any

from nav2_pyif_protocol.arrays import pack_poses, pack_xy
from nav2_pyif_protocol.codec import ErrorInfo, Reply, Request, encode_reply, encode_request
from nav2_pyif_protocol.constants import ErrorType, Op
from nav2_pyif_protocol.keys import KeySpace
from nav2_pyif_protocol.schema import BODIES, OP_TIMEOUT

#: Distinct values, so a client waiting with another class is caught.
TIMEOUTS = {"call": 0.04, "lifecycle": 1.5, "configure": 10.0, "plan": 3.0}
PREFIX = "nav2_pyif/transcript"
HOST_A = "host-a"
HOST_B = "host-b"
SESSION_UNKNOWN = ErrorInfo(ErrorType.SESSION_UNKNOWN.value, "no such session")
#: The host says nothing within the client's timeout.
SILENCE = None


@dataclass
class Plugin:
    """One plugin instance: what both clients are configured with, and its counters."""

    id: str
    type: str
    name: str
    node: str
    sid: str
    params: dict[str, Any] = field(default_factory=dict)
    global_frame: str = "odom"
    epoch: int = 0
    seq: int = 0

    @property
    def key(self) -> str:
        return f"{PREFIX}/{self.name}"

    def config(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "type": self.type,
            "key": self.key,
            "name": self.name,
            "node": self.node,
            "sid": self.sid,
            "params": self.params,
            "global_frame": self.global_frame,
            "robot_base_frame": "base_link",
        }


def controller() -> Plugin:
    return Plugin("controller", "controller", "FollowPath", "controller_server", "c" * 32,
                  {"max_vel_x": 0.5})  # fmt: skip


def goal_checker() -> Plugin:
    return Plugin("goal_checker", "goal_checker", "goal_checker", "controller_server", "9" * 32)


def progress_checker() -> Plugin:
    return Plugin("progress_checker", "progress_checker", "progress_checker",
                  "controller_server", "8" * 32)  # fmt: skip


def costmap(version: int, lethal: int) -> dict[str, Any]:
    """A 4 x 3 costmap in "odom" with one lethal cell at index ``lethal``."""
    data = bytearray(12)
    data[lethal] = 254
    return {
        "version": version,
        "frame_id": "odom",
        "size_x": 4,
        "size_y": 3,
        "resolution": 0.05,
        "origin_x": -0.1,
        "origin_y": -0.05,
        "data": bytes(data),
        "footprint": pack_xy([[0.2, 0.1], [0.2, -0.1], [-0.2, -0.1], [-0.2, 0.1]]),
        "robot_radius": 0.0,
    }


def pose7(x: float, y: float, yaw: float) -> list[float]:
    return [x, y, 0.0, 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)]


def stamped(x: float, y: float, yaw: float, stamp_ns: int) -> dict[str, Any]:
    return {"frame_id": "odom", "stamp_ns": stamp_ns, "pose": pose7(x, y, yaw)}


PLAN_ROWS = [pose7(0.25 * i, 0.0, 0.0) for i in range(5)]
PLAN = {"frame_id": "odom", "stamp_ns": 7, "poses": PLAN_ROWS}
TOLERANCES = {
    "xy_goal_tolerance": 0.25,
    "yaw_goal_tolerance": 0.5,
    "trans_stopped_velocity": 0.05,
    "rot_stopped_velocity": 0.1,
}
GOAL = pose7(1.0, 0.0, 0.0)


def wire_path(plan: dict[str, Any]) -> dict[str, Any]:
    return dict(plan, poses=pack_poses(plan["poses"]))


def ordered(op: Op, body: dict[str, Any]) -> dict[str, Any]:
    """``body`` in the schema's field order (as both clients write it)."""
    names = [f.name for f in BODIES[op][0]]
    return {name: body[name] for name in names if name in body}


def cmd(vx: float) -> dict[str, Any]:
    return {"frame_id": "base_link", "stamp_ns": 42, "twist": [vx, 0.0, 0.0, 0.0, 0.0, 0.1]}


class Script:
    """A transcript being written: steps, each a Nav2 call and the exchanges it makes."""

    def __init__(self, name: str, description: str, *plugins: Plugin, cycle: bool = False):
        self.name = name
        self.description = description
        self.plugins = {p.id: p for p in plugins}
        self.cycle = cycle
        self.costmap = costmap(1, 5)
        self.initial_costmap = self.costmap
        self.steps: list[dict[str, Any]] = []
        self.host: str | None = None  # the host pinned, for every exchange until changed

    # --- what happens around the client -----------------------------------------------------
    def hosts(self, *alive: str) -> None:
        """From now on these hosts' liveliness tokens are alive (the others' gone)."""
        self.steps.append({"hosts": sorted(alive)})

    def new_costmap(self, lethal: int) -> None:
        """The costmap changes (its version + 1)."""
        self.costmap = costmap(self.costmap["version"] + 1, lethal)
        self.steps.append({"costmap": _plain_costmap(self.costmap)})

    # --- Nav2's calls ---------------------------------------------------------------------
    def call(self, plugin: Plugin, call: str, **args: Any) -> dict[str, Any]:
        step: dict[str, Any] = {"plugin": plugin.id, "call": call}
        if args:
            step["args"] = args
        step["exchanges"] = []
        self.steps.append(step)
        return step

    def returns(self, value: Any) -> None:
        self.steps[-1]["returns"] = value

    def raises(self, error: str) -> None:
        self.steps[-1]["raises"] = error

    # --- the requests a call makes ---------------------------------------------------------
    def request(self, plugin: Plugin, op: Op, body: dict[str, Any]) -> Request:
        """The next request of ``plugin``'s session (configure starts a new epoch)."""
        plugin.epoch += op is Op.CONFIGURE
        plugin.seq += 1
        return Request(op=op, sid=plugin.sid, epoch=plugin.epoch, seq=plugin.seq, body=body)

    def exchange(
        self,
        plugin: Plugin,
        op: Op,
        body: dict[str, Any],
        reply: dict[str, Any] | ErrorInfo | None,
        host: str | None = None,
    ) -> None:
        """``plugin`` sends ``op`` to ``host`` (default: as the last exchange); the host
        answers ``reply`` (a body, an error, or SILENCE)."""
        self.host = host or self.host
        assert self.host is not None
        request = self.request(plugin, op, ordered(op, body))
        timeout = OP_TIMEOUT[op].value
        self.steps[-1]["exchanges"].append(
            {
                "op": op.value,
                "key": KeySpace(plugin.key).call(op),
                "host": self.host,
                "timeout": timeout,
                "timeout_s": TIMEOUTS[timeout],
                "request": encode_request(request).hex(),
                "reply": None if reply is None else self.reply(op, request.seq, reply).hex(),
            }
        )

    def reply(self, op: Op, seq: int, reply: dict[str, Any] | ErrorInfo) -> bytes:
        assert self.host is not None
        if isinstance(reply, ErrorInfo):
            return encode_reply(Reply(seq=seq, ok=False, host=self.host, error=reply), op)
        return encode_reply(Reply(seq=seq, ok=True, host=self.host, body=reply), op)

    def configure(self, plugin: Plugin, host: str | None = None) -> None:
        body = {
            "plugin_type": plugin.type,
            "name": plugin.name,
            "node": plugin.node,
            "params": plugin.params,
            "global_frame": plugin.global_frame,
            "robot_base_frame": "base_link",
            "costmap": self.costmap,
        }
        self.exchange(plugin, Op.CONFIGURE, body, {"declared": plugin.params}, host)

    def prepare(self, plugin: Plugin, op: Op, body: dict[str, Any]) -> Request:
        """A request prepared for another plugin's query to carry."""
        return self.request(plugin, op, ordered(op, body))

    def carry(self, *prepared: tuple[Plugin, Request]) -> list[dict[str, Any]]:
        return [{"key": p.key, "payload": encode_request(r)} for p, r in prepared]

    def carried(self, *answers: tuple[Plugin, Request, dict[str, Any]]) -> list[dict[str, Any]]:
        return [{"key": p.key, "payload": self.reply(r.op, r.seq, body)} for p, r, body in answers]

    def render(self) -> dict[str, Any]:
        return {
            "description": self.description,
            "timeouts": TIMEOUTS,
            "costmap": _plain_costmap(self.initial_costmap),
            "plugins": [p.config() for p in self.plugins.values()],
            "cycle": self.cycle,
            "steps": self.steps,
        }


def _plain_costmap(wire: dict[str, Any]) -> dict[str, Any]:
    """The costmap as a client holds it (the version is the client's count, not given)."""
    plain = {k: v for k, v in wire.items() if k != "version"}
    plain["data"] = wire["data"].hex()
    footprint = wire["footprint"]  # K x 2 little-endian float64, flattened
    plain["footprint"] = list(struct.unpack(f"<{len(footprint) // 8}d", footprint))
    return plain


# --- the transcripts ---------------------------------------------------------------------


def _start(s: Script, plugin: Plugin, host: str) -> None:
    """Nav2 configures and activates ``plugin``, on ``host``."""
    s.call(plugin, "configure")
    s.configure(plugin, host)
    s.call(plugin, "activate")
    s.exchange(plugin, Op.ACTIVATE, {}, {})


def _bring_up(s: Script, c: Plugin, host: str) -> None:
    """configure, activate and set_plan of controller ``c`` on ``host``."""
    _start(s, c, host)
    s.call(c, "set_plan", path=PLAN)
    s.exchange(c, Op.SET_PLAN, {"path": wire_path(PLAN)}, {})


def _reestablish(
    s: Script, c: Plugin, plan: dict[str, Any], plan_reply: dict[str, Any] | None = None
) -> None:
    """Controller ``c`` establishes its session again on the same host: configure, activate
    and the restored ``set_plan`` body ``plan``, answered ``plan_reply`` (None: silence)."""
    s.configure(c)
    s.exchange(c, Op.ACTIVATE, {}, {})
    s.exchange(c, Op.SET_PLAN, plan, plan_reply)


def _command_body(pose: dict[str, Any], velocity: list[float]) -> dict[str, Any]:
    return {"pose": pose, "velocity": velocity, "goal_checker": TOLERANCES}


def _command(
    s: Script,
    c: Plugin,
    pose: dict[str, Any],
    velocity: list[float],
    reply: dict[str, Any] | ErrorInfo | None,
    host: str | None = None,
) -> None:
    s.exchange(c, Op.COMPUTE_VELOCITY_COMMANDS, _command_body(pose, velocity), reply, host)


def restarted_host() -> Script:
    c = controller()
    s = Script(
        "restarted_host",
        "the host restarts (a new host id) and the costmap changes: the next cycle's "
        "SessionUnknown makes the client re-send configure (epoch 2, the new costmap), "
        "activate, the plan and the speed limit the planner last accepted (not the one it "
        "refused), then retry the cycle without the costmap",
        c,
    )
    s.hosts(HOST_A)
    _bring_up(s, c, HOST_A)
    s.call(c, "set_speed_limit", speed_limit=0.3, percentage=False)
    limit = {"speed_limit": 0.3, "percentage": False}
    s.exchange(c, Op.SET_SPEED_LIMIT, limit, {})
    s.call(c, "set_speed_limit", speed_limit=9.0, percentage=False)
    refused = ErrorInfo(ErrorType.CONTROLLER_EXCEPTION.value, "9.0 m/s is above max_vel_x")
    s.exchange(c, Op.SET_SPEED_LIMIT, {"speed_limit": 9.0, "percentage": False}, refused)
    s.raises("ControllerException")
    pose, velocity = stamped(0.1, 0.0, 0.0, 1000), [0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.3)})
    s.returns(cmd(0.3)["twist"])
    s.hosts(HOST_B)
    s.new_costmap(6)
    pose = stamped(0.2, 0.0, 0.0, 2000)
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    with_costmap = dict(_command_body(pose, velocity), costmap=s.costmap)
    s.exchange(c, Op.COMPUTE_VELOCITY_COMMANDS, with_costmap, SESSION_UNKNOWN, HOST_B)
    _reestablish(s, c, {"path": wire_path(PLAN)}, {})
    s.exchange(c, Op.SET_SPEED_LIMIT, limit, {})
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.4)})
    s.returns(cmd(0.4)["twist"])
    return s


def fail_over() -> Script:
    c = controller()
    s = Script(
        "fail_over",
        "two replicas: the client pins the smallest host id; when it does not answer a cycle "
        "in time the call goes to the other, whose SessionUnknown re-establishes the session "
        "there (configure, activate, plan) before the cycle is retried; later cycles stay there",
        c,
    )
    s.hosts(HOST_A, HOST_B)
    _bring_up(s, c, HOST_A)
    pose, velocity = stamped(0.1, 0.0, 0.0, 1000), [0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, SILENCE)
    _command(s, c, pose, velocity, SESSION_UNKNOWN,
               HOST_B)  # fmt: skip
    _reestablish(s, c, {"path": wire_path(PLAN)}, {})
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.3)})
    s.returns(cmd(0.3)["twist"])
    s.hosts(HOST_B)  # the silent replica's token goes at last
    pose = stamped(0.2, 0.0, 0.0, 2000)
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.4)})
    s.returns(cmd(0.4)["twist"])
    return s


def deferred_configure() -> Script:
    c = controller()
    s = Script(
        "deferred_configure",
        "Nav2 configures and activates the plugin before any host runs: nothing is sent, the "
        "plan is kept as owed (set_plan does not raise), and a speed limit fails at once but "
        "is kept; the first cycle once a host is alive establishes the session (configure, "
        "activate, the speed limit), sends the plan, then the cycle",
        c,
    )
    s.hosts()
    s.call(c, "defer_configure")
    s.call(c, "activate")
    s.call(c, "set_plan", path=PLAN)
    s.call(c, "set_speed_limit", speed_limit=40.0, percentage=True)
    s.raises("NoValidControl")
    s.hosts(HOST_A)
    pose, velocity = stamped(0.1, 0.0, 0.0, 1000), [0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    s.configure(c, HOST_A)
    s.exchange(c, Op.ACTIVATE, {}, {})
    s.exchange(c, Op.SET_SPEED_LIMIT, {"speed_limit": 40.0, "percentage": True}, {})
    s.exchange(c, Op.SET_PLAN, {"path": wire_path(PLAN)}, {})
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.3)})
    s.returns(cmd(0.3)["twist"])
    return s


def interrupted_restore() -> Script:
    c = controller()
    s = Script(
        "interrupted_restore",
        "a restarted host takes configure and activate but leaves the restored plan "
        "unanswered: the cycle fails, and the session is not taken as established with a "
        "host that lacks the plan; the next cycle establishes it again (epoch 3), plan "
        "included, before it is sent",
        c,
    )
    s.hosts(HOST_A)
    _bring_up(s, c, HOST_A)
    s.hosts(HOST_B)
    pose, velocity = stamped(0.1, 0.0, 0.0, 1000), [0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, SESSION_UNKNOWN, HOST_B)
    _reestablish(s, c, {"path": wire_path(PLAN)}, SILENCE)
    s.raises("NoValidControl")
    pose = stamped(0.2, 0.0, 0.0, 2000)
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _reestablish(s, c, {"path": wire_path(PLAN)}, {})
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.3)})
    s.returns(cmd(0.3)["twist"])
    return s


def followed_plan() -> Script:
    c = controller()
    s = Script(
        "followed_plan",
        "Lyrical: controller_server hands the controller the plan it transformed and the "
        "global goal every cycle (follow); a cycle carries each only when it changed since the "
        "host got it (stamps aside), and a restarted host gets both with set_plan",
        c,
    )
    s.hosts(HOST_A)
    _start(s, c, HOST_A)
    goal = stamped(1.0, 0.0, 0.0, 7)
    pose, velocity = stamped(0.1, 0.0, 0.0, 1000), [0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    s.call(c, "follow", path=PLAN, goal=goal)
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    body = dict(_command_body(pose, velocity), plan=wire_path(PLAN), goal=goal)
    s.exchange(c, Op.COMPUTE_VELOCITY_COMMANDS, body, {"cmd_vel": cmd(0.3)})
    s.returns(cmd(0.3)["twist"])
    pose = stamped(0.2, 0.0, 0.0, 2000)
    s.call(c, "follow", path=dict(PLAN, stamp_ns=2000), goal=dict(goal, stamp_ns=2000))
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.3)})
    s.returns(cmd(0.3)["twist"])
    s.hosts(HOST_B)
    pose = stamped(0.3, 0.0, 0.0, 3000)
    s.call(c, "follow", path=dict(PLAN, stamp_ns=3000), goal=dict(goal, stamp_ns=3000))
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, SESSION_UNKNOWN, HOST_B)
    _reestablish(s, c, {"path": wire_path(PLAN), "goal": goal}, {})
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.4)})
    s.returns(cmd(0.4)["twist"])
    return s


def silent_host() -> Script:
    c, g, p = controller(), goal_checker(), progress_checker()
    layer = Plugin("costmap_layer", "costmap_layer", "keepout", "local_costmap", "7" * 32)
    planner = Plugin("global_planner", "global_planner", "GridBased", "planner_server", "6" * 32)
    s = Script(
        "silent_host",
        "a host that answers configure and the lifecycle but nothing else: each call waits "
        "its op's timeout class (schema.OP_TIMEOUT; reset is a control-loop call for every "
        "plugin type, not a lifecycle one) and fails with its plugin type's host-failure "
        "exception",
        c,
        g,
        p,
        layer,
        planner,
    )
    s.hosts(HOST_A)
    for plugin in (c, g, p, layer, planner):
        s.call(plugin, "configure")
        s.configure(plugin, HOST_A)
    s.call(c, "activate")
    s.exchange(c, Op.ACTIVATE, {}, {})
    for plugin, error in (
        (c, "NoValidControl"),
        (g, "ControllerException"),
        (p, "ControllerException"),
        (layer, "ControllerException"),
    ):
        s.call(plugin, "reset")
        s.exchange(plugin, Op.RESET, {}, SILENCE)
        s.raises(error)
    pose, velocity = stamped(0.1, 0.0, 0.0, 1000), [0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, SILENCE)
    s.raises("NoValidControl")
    start, goal = stamped(0.0, 0.0, 0.0, 3000), stamped(0.1, 0.05, 0.0, 3000)
    s.call(planner, "create_plan", start=start, goal=goal)
    s.exchange(planner, Op.CREATE_PLAN, {"start": start, "goal": goal}, SILENCE)
    s.raises("PlannerException")
    s.call(c, "deactivate")
    s.exchange(c, Op.DEACTIVATE, {}, {})
    return s


def _cycle_plugins(s: Script, c: Plugin, g: Plugin, p: Plugin) -> None:
    s.hosts(HOST_A)
    s.call(g, "configure")
    s.configure(g, HOST_A)
    s.call(p, "configure")
    s.configure(p)
    _bring_up(s, c, HOST_A)


def _goal_check(pose: dict[str, Any], velocity: list[float]) -> dict[str, Any]:
    return {"pose": pose["pose"], "goal": GOAL, "velocity": velocity}


def carried_goal_first() -> Script:
    c, g, p = controller(), goal_checker(), progress_checker()
    s = Script(
        "carried_goal_first",
        "controller_server checks the goal first (Jazzy from 1.3.13, Kilted, Lyrical): the "
        "goal check's query carries the progress check and the command prepared for its pose "
        "and velocity, and those calls are answered from its reply: one query per cycle",
        c,
        g,
        p,
        cycle=True,
    )
    _cycle_plugins(s, c, g, p)
    velocity = [0.2, 0.0, 0.0, 0.0, 0.0, 0.05]
    for i, x in enumerate((0.1, 0.2)):
        pose = stamped(x, 0.0, 0.0, 1000 * (i + 1))
        s.call(g, "is_goal_reached", pose=pose, goal=GOAL, velocity=velocity,
               tolerances=TOLERANCES)  # fmt: skip
        check = s.prepare(p, Op.CHECK, {"pose": pose})
        command = s.prepare(c, Op.COMPUTE_VELOCITY_COMMANDS, _command_body(pose, velocity))
        body = dict(_goal_check(pose, velocity), carry=s.carry((p, check), (c, command)))
        answers = s.carried(
            (p, check, {"making_progress": True}), (c, command, {"cmd_vel": cmd(x)})
        )
        s.exchange(g, Op.IS_GOAL_REACHED, body, {"reached": False, "carried": answers})
        s.returns(False)
        s.call(p, "check", pose=pose)
        s.returns(True)
        s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
        s.returns(cmd(x)["twist"])
    return s


def carried_goal_last() -> Script:
    c, g, p = controller(), goal_checker(), progress_checker()
    s = Script(
        "carried_goal_last",
        "controller_server checks the goal last (Humble, Jazzy 1.3.8 to 1.3.12): the first "
        "cycle shows the order (three queries); from the next one the command's query "
        "carries the goal check for the goal last given, and the progress check goes alone",
        c,
        g,
        p,
        cycle=True,
    )
    _cycle_plugins(s, c, g, p)
    velocity = [0.2, 0.0, 0.0, 0.0, 0.0, 0.05]
    pose = stamped(0.1, 0.0, 0.0, 1000)
    s.call(p, "check", pose=pose)
    s.exchange(p, Op.CHECK, {"pose": pose}, {"making_progress": True})
    s.returns(True)
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    _command(s, c, pose, velocity, {"cmd_vel": cmd(0.1)})
    s.returns(cmd(0.1)["twist"])
    s.call(g, "is_goal_reached", pose=pose, goal=GOAL, velocity=velocity, tolerances=TOLERANCES)
    s.exchange(g, Op.IS_GOAL_REACHED, _goal_check(pose, velocity), {"reached": False})
    s.returns(False)
    pose = stamped(0.2, 0.0, 0.0, 2000)
    s.call(p, "check", pose=pose)
    s.exchange(p, Op.CHECK, {"pose": pose}, {"making_progress": True})
    s.returns(True)
    s.call(c, "compute_velocity_commands", **_command_body(pose, velocity))
    goal_check = s.prepare(g, Op.IS_GOAL_REACHED, _goal_check(pose, velocity))
    body = dict(_command_body(pose, velocity), carry=s.carry((g, goal_check)))
    answers = s.carried((g, goal_check, {"reached": True}))
    s.exchange(c, Op.COMPUTE_VELOCITY_COMMANDS, body, {"cmd_vel": cmd(0.2), "carried": answers})
    s.returns(cmd(0.2)["twist"])
    s.call(g, "is_goal_reached", pose=pose, goal=GOAL, velocity=velocity, tolerances=TOLERANCES)
    s.returns(True)
    return s


def behavior() -> Plugin:
    return Plugin("behavior", "behavior", "backup", "behavior_server", "b" * 32)


def behavior_restarted_host() -> Script:
    b = behavior()
    s = Script(
        "behavior_restarted_host",
        "a behaviour's host restarts while its action runs: the next cycle's SessionUnknown "
        "makes the client re-send configure, activate and the action's on_run (it goes on "
        "from its start), then retry the cycle; once the action completed, a restarted host "
        "gets no on_run",
        b,
    )
    s.hosts(HOST_A)
    _start(s, b, HOST_A)
    command = {"target_x": -0.3, "target_y": 0.0, "target_z": 0.0, "speed": 0.1}
    run = {
        "action": "nav2_msgs/action/BackUp",
        "command": command,
        "pose": stamped(0.0, 0.0, 0.0, 1),
    }
    s.call(b, "run", **run)
    s.exchange(b, Op.ON_RUN, run, {"status": "succeeded", "failure": ""})
    s.returns("succeeded")
    back = {"frame_id": "base_link", "stamp_ns": 42, "twist": [-0.1, 0.0, 0.0, 0.0, 0.0, 0.0]}
    cycle = {"pose": stamped(-0.05, 0.0, 0.0, 2), "elapsed": 0.5}
    running = {"status": "running", "failure": "", "cmd_vel": back}
    s.call(b, "cycle_update", **cycle)
    s.exchange(b, Op.ON_CYCLE_UPDATE, cycle, running)
    s.returns("running")
    s.hosts(HOST_B)
    s.call(b, "cycle_update", **cycle)
    s.exchange(b, Op.ON_CYCLE_UPDATE, cycle, SESSION_UNKNOWN, HOST_B)
    s.configure(b)
    s.exchange(b, Op.ACTIVATE, {}, {})
    s.exchange(b, Op.ON_RUN, run, {"status": "succeeded", "failure": ""})
    s.exchange(b, Op.ON_CYCLE_UPDATE, cycle, running)
    s.returns("running")
    s.call(b, "action_completion", status="succeeded", elapsed=3.0)
    s.exchange(b, Op.ON_ACTION_COMPLETION, {"status": "succeeded", "elapsed": 3.0}, {})
    s.hosts(HOST_A)
    s.call(b, "run", **run)
    s.exchange(b, Op.ON_RUN, run, SESSION_UNKNOWN, HOST_A)
    s.configure(b)
    s.exchange(b, Op.ACTIVATE, {}, {})
    s.exchange(b, Op.ON_RUN, run, {"status": "failed", "failure": "collision_ahead"})
    s.returns("failed")
    return s


TRANSCRIPTS = (
    restarted_host,
    fail_over,
    deferred_configure,
    interrupted_restore,
    followed_plan,
    silent_host,
    carried_goal_first,
    carried_goal_last,
    behavior_restarted_host,
)


def rendered_transcripts() -> dict[str, bytes]:
    """transcripts/<name>.json -> its content."""
    files = {}
    for make in TRANSCRIPTS:
        script = make()
        text = json.dumps(script.render(), indent=1) + "\n"
        files[f"transcripts/{script.name}.json"] = text.encode()
    return files
