"""A hot swap configures each live session once on the new planner, then catches it up with
only what changed while the new planner was taking the sessions: the parameters, the costmap,
the plan, a session configured meanwhile, and a cleanup of one that ended (before, the new
planner's configure ran twice on a swap). Real planner runtimes, real encoded requests, the host's
own journal; the plugin's calls arrive while the new planner configures its first session."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import nullcontext
from typing import Any

import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif import Plan
from nav2_pyif.client.controller import ControllerClient
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif_protocol.codec import Request, decode_reply, encode_request
from nav2_pyif_protocol.constants import Op, PluginType

from tests.conftest import configure_body, make_costmap
from tests.fixtures.echo_planners import EchoController

pytestmark = pytest.mark.unit

CONFIGURES: list[str] = []  # the session id of each configure of the new planner


class CountedEcho(EchoController):
    """EchoController whose configures are counted."""

    def configure(self) -> None:
        CONFIGURES.append(self.name)
        super().configure()


class Plugin:
    """One plugin's session, served by ``old`` as the host serves it (each ok reply noted in
    the journal)."""

    def __init__(self, name: str, old: PlannerRuntime, journal: Journal) -> None:
        self.sid, self.name, self.old, self.journal, self.seq = name * 32, name, old, journal, 0

    def call(self, op: Op, body: dict[str, Any], runtime: PlannerRuntime | None = None) -> Any:
        self.seq += 1
        payload = encode_request(Request(op, self.sid[:32], 1, self.seq, body))
        reply = (runtime or self.old).handle(payload, op.value)
        if runtime is None:
            self.journal.note(op.value, payload, reply)
        answer = decode_reply(reply, op)
        assert answer.ok, answer.error
        return answer.body

    def configure(self, gain: float) -> None:
        self.call(Op.CONFIGURE, configure_body(name=self.name, params={"gain": gain}))
        self.call(Op.ACTIVATE, {})

    def set_plan(self, poses: int) -> None:
        self.call(Op.SET_PLAN, {"path": Plan(np.zeros((poses, 3)), "odom").to_wire()})

    def cycle(self, runtime: PlannerRuntime | None = None, costmap: int = 0) -> Any:
        """linear.x: the plan's length; linear.y: the gain; angular.x: the costmap version."""
        pose = PoseStamped()
        pose.header.frame_id = "odom"
        body = ControllerClient.compute_body(pose, Twist())
        if costmap:
            body["costmap"] = make_costmap(version=costmap).to_wire()
        reply = self.call(Op.COMPUTE_VELOCITY_COMMANDS, body, runtime)
        twist = reply["cmd_vel"]["twist"]
        return twist[0], twist[1], twist[3]


def _meanwhile(
    new: PlannerRuntime, during: Callable[[], None]
) -> Callable[[str, bytes], bytes | None]:
    """The new planner's call path; ``during`` runs as its first request (a configure) starts,
    as the plugins' calls reach the old planner while the new one configures."""
    pending = [during]

    def call(op: str, payload: bytes) -> bytes | None:
        while pending:
            pending.pop()()
        return new.handle(payload, op)

    return call


def test_a_swap_configures_each_session_once_and_catches_up_only_what_changed() -> None:
    journal, old = Journal(), PlannerRuntime(EchoController, "old-host")
    kept, ended = Plugin("a", old, journal), Plugin("b", old, journal)
    for plugin in (kept, ended):
        plugin.configure(gain=2.0)
        plugin.set_plan(5)
    late = Plugin("c", old, journal)

    def plugins_meanwhile() -> None:
        kept.call(Op.SET_PARAMETERS, {"params": {"gain": 3.0}})
        kept.set_plan(7)
        kept.cycle(costmap=2)  # a new costmap comes with a cycle
        ended.call(Op.DEACTIVATE, {})
        ended.call(Op.CLEANUP, {})
        late.configure(gain=4.0)

    CONFIGURES.clear()
    new = PlannerRuntime(CountedEcho, "new-host")
    carried = journal.hand_over(
        _meanwhile(new, plugins_meanwhile),
        ("CountedEcho", PluginType.CONTROLLER),
        PluginType.CONTROLLER,
        nullcontext(),
        lambda: None,
    )
    assert carried == 2
    assert sorted(CONFIGURES) == ["a", "b", "c"]  # once each: "a" changed, never re-configured
    assert set(new.sessions) == {kept.sid, late.sid}  # "b" ended meanwhile: cleaned up
    assert kept.cycle(new) == (7.0, 3.0, 2.0)  # the plan, the gain and the costmap since
    assert late.cycle(new)[1] == 4.0
    assert new.sessions[kept.sid].active


def test_a_session_reconfigured_meanwhile_is_configured_again_whole() -> None:
    journal, old = Journal(), PlannerRuntime(EchoController, "old-host")
    plugin = Plugin("a", old, journal)
    plugin.configure(gain=2.0)
    CONFIGURES.clear()
    new = PlannerRuntime(CountedEcho, "new-host")
    journal.hand_over(
        _meanwhile(new, lambda: plugin.configure(gain=5.0)),
        ("CountedEcho", PluginType.CONTROLLER),
        PluginType.CONTROLLER,
        nullcontext(),
        lambda: None,
    )
    assert CONFIGURES == ["a", "a"]  # the plugin configured it twice itself
    assert plugin.cycle(new)[1] == 5.0
