"""What a peer can make a planner host keep is bounded: the sessions of one served planner (in
the worker and in the host's journal) and the input names of one session. Found by the hostile
peer: mutated configures are new sessions more often than not, and mutated inputs new names,
and each grew the worker for good (RELIABILITY.md, "The hostile peer")."""

from __future__ import annotations

import gc
import logging
import random
import sys
import warnings
from typing import Any

import nav2_pyif.inputs
import pytest
from nav2_pyif._ros_types import serialize
from nav2_pyif.inputs import Inputs
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif.server.session_limit import IDLE_S
from nav2_pyif_bench.mutations import load_seeds, mutate
from nav2_pyif_protocol.codec import Request, encode_request
from nav2_pyif_protocol.constants import MAX_INPUTS, Op
from sensor_msgs.msg import Imu

from tests.conftest import configure_body
from tests.fixtures.echo_planners import EchoController
from tests.test_runtime import Driver

pytestmark = pytest.mark.unit

CONFIGURE = configure_body()


@pytest.fixture
def runtime() -> PlannerRuntime:
    runtime = PlannerRuntime(EchoController, "test-host")
    runtime.max_sessions = 3
    for sid in ("a", "b", "c"):
        assert Driver(runtime).call(Op.CONFIGURE, CONFIGURE, sid).ok
    return runtime


def test_a_new_session_beyond_the_limit_is_refused_while_every_one_is_in_use(
    runtime: PlannerRuntime,
) -> None:
    refused = Driver(runtime).call(Op.CONFIGURE, CONFIGURE, "d")
    assert not refused.ok and refused.error is not None
    assert "serves 3 sessions already" in refused.error.message
    assert set(runtime.sessions) == {"a", "b", "c"}
    assert (
        Driver(runtime).call(Op.CONFIGURE, CONFIGURE, "b").ok
    )  # one of them again: no new session


def test_a_new_session_ends_the_one_idle_longest(runtime: PlannerRuntime) -> None:
    runtime.sessions["a"].last_call -= IDLE_S + 30  # its Nav2 went away, no cleanup sent
    runtime.sessions["b"].last_call -= IDLE_S + 5
    cleaned: list[str] = []
    runtime.sessions["a"].planner.cleanup = lambda: cleaned.append("a")  # type: ignore[method-assign]
    assert Driver(runtime).call(Op.CONFIGURE, CONFIGURE, "d").ok
    assert set(runtime.sessions) == {"b", "c", "d"}
    assert cleaned == ["a"]  # its planner was cleaned up
    gone = Driver(runtime).call(Op.ACTIVATE, {}, "a")
    assert gone.error is not None and gone.error.type == "SessionUnknown"  # a live plugin
    # would configure again on this reply; here "b" is now the one idle longest
    assert Driver(runtime).call(Op.CONFIGURE, CONFIGURE, "a").ok
    assert set(runtime.sessions) == {"c", "d", "a"}


def test_a_call_keeps_a_session_from_counting_as_idle(runtime: PlannerRuntime) -> None:
    for sid in ("a", "b", "c"):
        runtime.sessions[sid].last_call -= IDLE_S + 10
    assert Driver(runtime).call(Op.ACTIVATE, {}, "a").ok
    assert Driver(runtime).call(Op.CONFIGURE, CONFIGURE, "d").ok
    assert set(runtime.sessions) == {"a", "c", "d"}  # b, idle longest of the two idle


def test_the_journal_keeps_as_many_sessions_forgetting_the_one_heard_from_least() -> None:
    journal = Journal()
    journal.max_sessions = 3
    ok = b"\x82\xa2ok\xc3\xa4body\x80"  # {"ok": true, "body": {}}
    for sid in ("a", "b", "c"):
        journal.note("configure", encode_request(Request(Op.CONFIGURE, sid, 1, 1, CONFIGURE)), ok)
    journal.note("activate", encode_request(Request(Op.ACTIVATE, "a", 1, 2, {})), ok)
    journal.note("configure", encode_request(Request(Op.CONFIGURE, "d", 1, 3, CONFIGURE)), ok)
    assert set(journal.records()) == {"a", "c", "d"}
    assert journal.records()["a"].active


def _imu(name: str, stamp_ns: int = 1) -> dict[str, Any]:
    return {"name": name, "type": "sensor_msgs/msg/Imu", "stamp_ns": stamp_ns, "cdr": IMU}


IMU = serialize(Imu())


def test_a_session_keeps_at_most_max_inputs_input_names() -> None:
    inputs = Inputs()
    inputs.update([_imu(f"imu{i}") for i in range(MAX_INPUTS)])
    with pytest.raises(ValueError, match=f"more than {MAX_INPUTS} input names"):
        inputs.update([_imu("imu3", 2), _imu("one_more")])
    assert len(inputs) == MAX_INPUTS and inputs.received_ns("imu3") == 1  # nothing half-done
    inputs.update([_imu("imu3", 3)])  # the names it has still update
    assert inputs.received_ns("imu3") == 3


def test_mutated_requests_leave_the_worker_no_bigger_than_its_bounds(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The hostile peer's traffic, in process: what it leaves alive stays bounded, once the
    bounds are reached (small ones here, to reach them quickly). Without them, these 10 500
    mutated configures and cycles with inputs left 26 sessions, each with its input names,
    and 1 079 more live memory blocks over the last three batches (433 with them)."""
    monkeypatch.setattr(nav2_pyif.inputs, "MAX_INPUTS", 8)
    quiet = logging.getLogger("nav2_pyif.test.session_bounds")  # pytest keeps every record
    quiet.propagate = False
    runtime = PlannerRuntime(EchoController, "test-host", logger=quiet)
    runtime.max_sessions = 2
    seeds = load_seeds("request")
    rng = random.Random(3)
    hostile = [seeds["configure_controller"], seeds["compute_velocity_commands_inputs"]]

    def batch() -> int:
        """Live memory blocks after 1 500 mutated requests (after a full collection: the
        garbage the collector has yet to reach is not kept)."""
        for _ in range(1500):
            op, data = rng.choice(hostile)
            runtime.handle(mutate(rng, data), op)
        gc.unfreeze()
        gc.collect()
        gc.freeze()
        return sys.getallocatedblocks()

    with warnings.catch_warnings():  # pytest keeps every warning too (numpy's, on odd inputs)
        warnings.simplefilter("ignore")
        for _, (op, data) in seeds.items():
            runtime.handle(data, op)
        for _ in range(3):
            batch()  # warm: the bounds reached, the inputs' message types loaded
        live = [batch() for _ in range(4)]
    assert live[-1] - live[0] < 800, live
    assert len(runtime.sessions) <= 2
    assert all(len(s.context.inputs) <= 8 for s in runtime.sessions.values())
