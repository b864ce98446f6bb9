"""The reference client replays the shared session transcripts (protocol/vectors/transcripts,
PROTOCOL.md section 18) through its transport seam: a MockTransport that checks each request
byte for byte, with the key, the replica and the timeout it waits, and answers from the
transcript; silence costs no time. The C++ plugin replays the same files
(bridge_plugin/test/client/transcripts_test.cpp)."""

from __future__ import annotations

import json
from collections import deque
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from nav2_pyif._messages import pose_from_wire, twist_from_list, twist_to_list
from nav2_pyif.client import (
    BehaviorClient,
    ControlCycle,
    ControllerClient,
    CostmapLayerClient,
    GlobalPlannerClient,
    GoalCheckerClient,
    PluginClient,
    ProgressCheckerClient,
    Timeouts,
)
from nav2_pyif.client.transport import MockTransport, StaticHosts
from nav2_pyif.costmap import Costmap
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.plan import Plan
from nav2_pyif_protocol.codec import decode_request

pytestmark = pytest.mark.unit

TRANSCRIPTS = Path(__file__).resolve().parents[1] / "protocol" / "vectors" / "transcripts"
CLIENTS: dict[str, type[PluginClient]] = {
    "controller": ControllerClient,
    "goal_checker": GoalCheckerClient,
    "progress_checker": ProgressCheckerClient,
    "costmap_layer": CostmapLayerClient,
    "global_planner": GlobalPlannerClient,
    "behavior": BehaviorClient,
}


def _costmap(plain: dict[str, Any], version: int) -> Costmap:
    data = np.frombuffer(bytes.fromhex(plain["data"]), dtype=np.uint8)
    return Costmap(
        data.reshape(plain["size_y"], plain["size_x"]),
        plain["resolution"],
        plain["origin_x"],
        plain["origin_y"],
        plain["frame_id"],
        np.array(plain["footprint"]).reshape(-1, 2),
        plain["robot_radius"],
        version,
    )


def _readable(payload: bytes) -> str:
    try:
        request = decode_request(payload)
    except Exception as exc:  # shown, not judged: the byte comparison failed already
        return f"<undecodable: {exc}>"
    return f"{request.op.value} epoch {request.epoch} seq {request.seq} {request.body!r}"


class Replay:
    """One transcript's plugins on a MockTransport that expects its exchanges in order."""

    def __init__(self, transcript: dict[str, Any]) -> None:
        self.hosts = StaticHosts()
        self.expected: deque[dict[str, Any]] = deque()
        transport = MockTransport(self.answer, self.hosts)
        self.costmap_version = 1
        costmap = _costmap(transcript["costmap"], self.costmap_version)
        timeouts = Timeouts(**transcript["timeouts"])
        self.clients: dict[str, PluginClient] = {}
        for p in transcript["plugins"]:
            self.clients[p["id"]] = CLIENTS[p["type"]](
                transport,
                p["key"],
                costmap,
                name=p["name"],
                node=p["node"],
                params=p["params"],
                global_frame=p["global_frame"],
                robot_base_frame=p["robot_base_frame"],
                timeouts=timeouts,
                sid=p["sid"],
            )
        self.cycle: ControlCycle | None = None
        if transcript["cycle"]:
            c = self.clients
            self.cycle = ControlCycle(c["controller"], c["goal_checker"], c["progress_checker"])  # type: ignore[arg-type]

    def answer(self, key: str, host: str | None, payload: bytes, timeout: float) -> bytes | None:
        assert self.expected, f"a request the transcript does not have: {_readable(payload)}"
        e = self.expected.popleft()
        sent = {"key": key, "host": host, "timeout_s": timeout}
        wanted = {name: e[name] for name in sent}
        assert sent == wanted, f"{e['op']}: sent to {sent}, the transcript says {wanted}"
        assert payload.hex() == e["request"], (
            f"{e['op']} differs:\n sent     {_readable(payload)}\n expected "
            f"{_readable(bytes.fromhex(e['request']))}"
        )
        return None if e["reply"] is None else bytes.fromhex(e["reply"])

    def step(self, step: dict[str, Any]) -> None:
        if "hosts" in step:
            self.hosts.set(step["hosts"])
            return
        if "costmap" in step:
            self.costmap_version += 1
            for client in self.clients.values():
                client.update_costmap(_costmap(step["costmap"], self.costmap_version))
            return
        self.expected.extend(step["exchanges"])
        where = f"{step['plugin']}.{step['call']}"
        if "raises" in step:
            with pytest.raises(Exception) as raised:
                self.call(step)
            if isinstance(raised.value, AssertionError):
                raise raised.value  # the transcript's check, not the client's exception
            assert type(raised.value).__name__ == step["raises"], f"{where}: {raised.value!r}"
        else:
            returned = self.call(step)
            if "returns" in step:
                assert returned == step["returns"], where
        assert not self.expected, f"{where} did not send {[e['op'] for e in self.expected]}"

    def call(self, step: dict[str, Any]) -> Any:
        client, name, args = self.clients[step["plugin"]], step["call"], step.get("args", {})
        if name == "set_plan":
            plan = args["path"]
            assert isinstance(client, ControllerClient)
            return client.set_plan(Plan(plan["poses"], plan["frame_id"], plan["stamp_ns"]))
        if name == "follow":
            plan, goal = args["path"], pose_from_wire(args["goal"])
            assert isinstance(client, ControllerClient)
            return client.follow(Plan(plan["poses"], plan["frame_id"], plan["stamp_ns"]), goal)
        if name == "set_speed_limit":
            assert isinstance(client, ControllerClient)
            return client.set_speed_limit(args["speed_limit"], args["percentage"])
        if name == "compute_velocity_commands":
            pose, velocity = pose_from_wire(args["pose"]), twist_from_list(args["velocity"])
            tolerances = GoalTolerances.from_wire(args["goal_checker"])
            if self.cycle is not None:
                cmd = self.cycle.compute_velocity_commands(pose, velocity, tolerances)
            else:
                assert isinstance(client, ControllerClient)
                cmd = client.compute_velocity_commands(pose, velocity, tolerances)
            return twist_to_list(cmd.twist)
        if name == "is_goal_reached":
            pose, velocity = pose_from_wire(args["pose"]), twist_from_list(args["velocity"])
            goal = pose_from_wire(dict(args["pose"], pose=args["goal"])).pose
            if self.cycle is not None:
                tolerances = GoalTolerances.from_wire(args["tolerances"])
                return self.cycle.is_goal_reached(pose, goal, velocity, tolerances)
            assert isinstance(client, GoalCheckerClient)
            return client.is_goal_reached(pose.pose, goal, velocity)
        if name == "check":
            pose = pose_from_wire(args["pose"])
            if self.cycle is not None:
                return self.cycle.check(pose)
            assert isinstance(client, ProgressCheckerClient)
            return client.check(pose)
        if name == "create_plan":
            assert isinstance(client, GlobalPlannerClient)
            return client.create_plan(pose_from_wire(args["start"]), pose_from_wire(args["goal"]))
        if name == "run":
            assert isinstance(client, BehaviorClient)
            status, _ = client.run(args["action"], args["command"], pose_from_wire(args["pose"]))
            return status.value
        if name == "cycle_update":
            assert isinstance(client, BehaviorClient)
            return client.cycle_update(pose_from_wire(args["pose"]), args["elapsed"]).status.value
        if name == "action_completion":
            assert isinstance(client, BehaviorClient)
            return client.action_completion(args["status"], args["elapsed"])
        assert not args, f"{name} takes no arguments"
        return getattr(client, name)()  # configure, defer_configure, the lifecycle, reset


@pytest.mark.parametrize("path", sorted(TRANSCRIPTS.glob("*.json")), ids=lambda p: p.stem)
def test_the_reference_client_replays_the_transcript(path: Path) -> None:
    transcript = json.loads(path.read_text())
    replay = Replay(transcript)
    for step in transcript["steps"]:
        replay.step(step)


def test_every_transcript_is_replayed() -> None:
    names = {p.stem for p in TRANSCRIPTS.glob("*.json")}
    assert {"restarted_host", "fail_over", "deferred_configure", "silent_host"} <= names
    assert {"interrupted_restore"} <= names
    assert {"carried_goal_first", "carried_goal_last", "behavior_restarted_host"} <= names
