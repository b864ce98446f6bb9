"""The batch gate's own rules, on real threads with a recording planner service in place of a
worker: a handed-over control cycle is answered from the batch's thread, a key's next call
of another op waits for its cycle, and one robot's failed answer does not stop the others."""

from __future__ import annotations

import threading
from collections.abc import Iterator

import msgpack
import pytest
from nav2_pyif.server.batch_gate import BatchGroup
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.spec import PlannerSpec
from nav2_pyif_protocol.constants import ErrorType, PluginType

pytestmark = pytest.mark.unit


class RecordingService:
    """A PlannerService that records what reaches the planner; a batch waits for ``release``."""

    plugin_type = PluginType.CONTROLLER
    isolation = "none"
    swapped_at = 0.0
    label = "recording"
    where = "in process"

    def __init__(self) -> None:
        self.journal = Journal()
        self.calls: list[tuple[str, object]] = []
        self.release = threading.Event()
        self.batch_started = threading.Event()

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        self.calls.append(("call", payload))
        return b"done " + payload

    def handle_batch(self, payloads: list[bytes]) -> list[bytes]:
        self.batch_started.set()
        assert self.release.wait(10.0), "the test never released the batch"
        self.calls.append(("batch", tuple(payloads)))
        return [b"reply to " + payload for payload in payloads]

    def handle_cancel(self, payload: bytes) -> bytes:
        return b""

    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str:
        return "not reloaded"

    def close(self) -> None:
        pass


@pytest.fixture
def service() -> RecordingService:
    return RecordingService()


@pytest.fixture
def group(service: RecordingService) -> Iterator[BatchGroup]:
    group = BatchGroup(service, "host", window=0.0, period=1.0)
    yield group
    service.release.set()
    group.batcher.close()


def test_a_handed_over_cycle_is_answered_on_the_batchs_answering_thread(
    service: RecordingService, group: BatchGroup
) -> None:
    answered: list[tuple[bytes, str]] = []
    done = threading.Event()

    def answer(reply: bytes) -> None:
        answered.append((reply, threading.current_thread().name))
        done.set()

    group.member("robot0").submit_cycle(b"cycle", answer)  # returns at once
    service.release.set()
    assert done.wait(5.0)
    # not the key's thread, nor the one feeding the planner: it runs the next batch meanwhile
    assert answered == [(b"reply to cycle", "answers:recording")]


def test_a_keys_next_call_waits_for_its_cycle_in_a_batch(
    service: RecordingService, group: BatchGroup
) -> None:
    member = group.member("robot0")
    member.submit_cycle(b"cycle", lambda reply: None)
    assert service.batch_started.wait(5.0)
    replies: list[bytes] = []
    later = threading.Thread(target=lambda: replies.append(member.handle(b"plan", "set_plan")))
    later.start()
    later.join(0.3)
    assert later.is_alive() and service.calls == []  # set_plan waits behind the cycle
    service.release.set()
    later.join(5.0)
    assert service.calls == [("batch", (b"cycle",)), ("call", b"plan")]
    assert replies == [b"done plan"]


def test_one_robots_failed_answer_leaves_the_others_answered(
    service: RecordingService, group: BatchGroup
) -> None:
    group.member("robot0").submit_cycle(b"first", lambda reply: None)
    assert service.batch_started.wait(5.0)  # the next two cycles wait: one batch together
    answered: list[bytes] = []
    third = threading.Event()

    def gone(reply: bytes) -> None:
        raise ConnectionError("that robot's session is closed")

    group.member("robot1").submit_cycle(b"second", gone)

    def fine(reply: bytes) -> None:
        answered.append(reply)
        third.set()

    group.member("robot2").submit_cycle(b"third", fine)
    service.release.set()
    assert third.wait(5.0)
    assert answered == [b"reply to third"]
    assert service.calls[-1] == ("batch", (b"second", b"third"))
    after = threading.Event()
    group.member("robot1").submit_cycle(b"fourth", lambda reply: after.set())
    assert after.wait(5.0)  # the batch thread went on


def test_a_robots_newer_cycle_supersedes_its_older_one_still_waiting(
    service: RecordingService, group: BatchGroup
) -> None:
    """Overload: a robot whose cycle ran out of time sends the next one; the older one, not
    yet computed, is answered at once (Unavailable) and only the newer one is computed."""
    group.member("robot0").submit_cycle(b"running", lambda reply: None)
    assert service.batch_started.wait(5.0)
    older: list[bytes] = []
    newer = threading.Event()
    robot1 = group.member("robot1")
    robot1.submit_cycle(b"older", older.append)
    robot1.submit_cycle(b"newer", lambda reply: newer.set())
    answer = msgpack.unpackb(older[0])  # answered before the running batch ended
    assert not answer["ok"] and answer["error"]["type"] == ErrorType.UNAVAILABLE.value
    assert "superseded" in answer["error"]["message"]
    service.release.set()
    assert newer.wait(5.0)
    assert service.calls[-1] == ("batch", (b"newer",))
    assert group.batcher.superseded == 1
