"""One planner for a fleet: the keys of a batch group share one served planner (one worker),
and their control cycles that arrive within the batch window become one batched call.

A batch leaves when every key that called in the last two control periods has a cycle in it
(a lone robot waits for nothing), or when its first cycle has waited the window, whichever
is first; cycles that arrive while a batch runs form the next one. A cycle that waited more
than a control period (an overloaded host) is answered Unavailable without being computed.
Every other call (configure, set_plan, parameters, ...) goes straight to the shared planner,
between two batches, once that key's last cycle is answered.

The batch's answering thread answers each cycle itself (``submit_nowait``): the key's own
thread hands its query over and goes back to its queue. Waking each key's thread to answer
after every batch cost the host most of its time at 100 robots: a burst of threads contending
for the GIL while the next batch waited for it. The answers are sent while the next batch
runs, not before it: at 120 robots, sending a batch's 100 replies took 6 ms of a 40 ms cycle
on the one thread that also feeds the planner.
"""

from __future__ import annotations

import logging
import queue
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from nav2_pyif_protocol.constants import ErrorType, PluginType

from nav2_pyif.server.batch_runtime import CYCLE_OP
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.runtime import error_reply, peek_seq
from nav2_pyif.server.service import PlannerService
from nav2_pyif.server.spec import PlannerSpec

log = logging.getLogger("nav2_pyif.server.host")

#: The window may be at most this fraction of the control period: a cycle's wait for its
#: batch must leave the period to the computation and the round trip.
MAX_WINDOW_FRACTION = 0.25


def check_window(window: float, period: float) -> None:
    """A ValueError unless 0 <= ``window`` <= MAX_WINDOW_FRACTION x ``period``."""
    if period <= 0:
        raise ValueError(f"the control period must be > 0 s (got {period:g})")
    if not 0 <= window <= MAX_WINDOW_FRACTION * period:
        raise ValueError(
            f"the batch window ({window * 1000:g} ms) must lie between 0 and "
            f"{MAX_WINDOW_FRACTION:g} x the control period ({period * 1000:g} ms): at most "
            f"{MAX_WINDOW_FRACTION * period * 1000:g} ms"
        )


#: Sends a cycle's reply to the robot (a query's reply); called on the batch's thread
Answer = Callable[[bytes], None]


@dataclass
class _Cycle:
    member: str
    payload: bytes
    arrived: float
    answer: Answer | None = None  # None: the submitting thread waits for ``reply``
    reply: bytes = b""
    done: threading.Event = field(default_factory=threading.Event)

    def finish(self, reply: bytes) -> None:
        self.reply = reply
        if self.answer is not None:
            try:
                self.answer(reply)
            except Exception:  # the robot is gone, the session closed: the others go on
                log.exception("could not answer a control cycle of %s", self.member)
        self.done.set()


class Batcher:
    """Gathers control cycles from several keys and runs them as one batch on a thread."""

    def __init__(
        self,
        run: Callable[[list[bytes]], list[bytes]],
        window: float,
        period: float,
        host_id: str,
        name: str,
    ) -> None:
        self.run, self.window, self.period, self.host_id = run, window, period, host_id
        self.batches = 0  # batched calls made
        self.cycles = 0  # control cycles they served
        self.dropped = 0  # cycles answered without computing: older than a control period
        self.superseded = 0  # ... or followed by the same robot's next cycle
        self._cond = threading.Condition()
        self._pending: list[_Cycle] = []  # the next batch, in arrival order
        self._queued: dict[str, _Cycle] = {}  # member key -> its cycle in the next batch
        self._last_call: dict[str, float] = {}  # member key -> when it last sent a cycle
        self._closing = False
        # batches computed, with their replies, for the answering thread; None: no more
        self._answers: queue.SimpleQueue[list[tuple[_Cycle, bytes]] | None] = queue.SimpleQueue()
        self._threads = [
            threading.Thread(target=self._serve, name=f"batch:{name}", daemon=True),
            threading.Thread(target=self._answer, name=f"answers:{name}", daemon=True),
        ]
        for thread in self._threads:
            thread.start()

    def submit(self, member: str, payload: bytes) -> bytes:
        """The reply to one control cycle, once its batch ran."""
        cycle = self.submit_nowait(member, payload)
        cycle.done.wait()
        return cycle.reply

    def submit_nowait(self, member: str, payload: bytes, answer: Answer | None = None) -> _Cycle:
        """Queue one control cycle; ``answer`` gets its reply on the batch's thread."""
        cycle = _Cycle(member, payload, time.monotonic(), answer)
        with self._cond:
            closing, older = self._closing, self._queued.pop(member, None)
            if older is not None:
                self._pending.remove(older)
            if not closing:
                self._pending.append(cycle)
                self._queued[member] = cycle
                self._last_call[member] = cycle.arrived
                self._cond.notify()
        if older is not None:
            self._supersede(older)
        if closing:
            cycle.finish(self._refused(payload, "the planner host is shutting down"))
        return cycle

    def _supersede(self, older: _Cycle) -> None:
        """A robot sends its next cycle when the last one ran out of time (an overload): the
        older one, not yet computed, is answered at once. Computing both would double that
        robot's load at the moment the host has least to spare, and keep it overloaded."""
        self.superseded += 1
        older.finish(
            self._refused(
                older.payload,
                "superseded: the robot sent a newer control cycle before this one's batch "
                "ran (this one had timed out); not computed",
            )
        )

    def _callers(self, now: float) -> int:
        """Keys that sent a cycle in the last two control periods: the batch to wait for."""
        recent = now - 2 * self.period
        for member in [m for m, t in self._last_call.items() if t < recent]:
            del self._last_call[member]
        return len(self._last_call)

    def _next_batch(self) -> list[_Cycle] | None:
        with self._cond:
            while not self._pending and not self._closing:
                self._cond.wait()
            if self._closing:
                return None
            leave_at = self._pending[0].arrived + self.window
            while True:
                now = time.monotonic()
                waiting = {cycle.member for cycle in self._pending}
                if len(waiting) >= self._callers(now) or now >= leave_at or self._closing:
                    break
                self._cond.wait(leave_at - now)
            batch, self._pending = self._pending, []
            self._queued.clear()
            return batch

    def _drop_stale(self, batch: list[_Cycle]) -> list[_Cycle]:
        """Overload: a cycle that waited a whole control period for its batch is answered
        at once, not computed (its plugin, whose timeout is below the period, has given up;
        a robot's next cycle is already on its way): late work never delays the next batch."""
        oldest = time.monotonic() - self.period
        fresh = [cycle for cycle in batch if cycle.arrived >= oldest]
        for cycle in batch:
            if cycle.arrived < oldest:
                self.dropped += 1
                waited = (time.monotonic() - cycle.arrived) * 1000
                cycle.finish(
                    self._refused(
                        cycle.payload,
                        f"overloaded: this control cycle waited {waited:.0f} ms for its batch, "
                        f"more than the {self.period * 1000:g} ms control period; not computed",
                    )
                )
        return fresh

    def _serve(self) -> None:
        while (batch := self._next_batch()) is not None:
            batch = self._drop_stale(batch)
            if not batch:
                continue
            try:
                replies = self.run([cycle.payload for cycle in batch])
            except Exception as exc:  # the service never raises; if it did, no robot hangs
                log.exception("a batch of %d control cycles failed", len(batch))
                replies = [self._refused(c.payload, f"the batch failed: {exc}") for c in batch]
            self.batches += 1
            self.cycles += len(batch)
            self._answers.put(list(zip(batch, replies, strict=True)))
        with self._cond:  # closing: nobody is left waiting
            left, self._pending = self._pending, []
            self._queued.clear()
        self._answers.put(
            [(c, self._refused(c.payload, "the planner host is shutting down")) for c in left]
        )
        self._answers.put(None)

    def _answer(self) -> None:
        while (answers := self._answers.get()) is not None:
            for cycle, reply in answers:
                cycle.finish(reply)

    def _refused(self, payload: bytes, why: str) -> bytes:
        return error_reply(peek_seq(payload), self.host_id, ErrorType.UNAVAILABLE, why)

    def close(self) -> None:
        with self._cond:
            self._closing = True
            self._cond.notify_all()
        for thread in self._threads:
            thread.join(10.0)


class BatchGroup:
    """The keys served by one planner whose control cycles are batched."""

    def __init__(self, service: PlannerService, host_id: str, window: float, period: float) -> None:
        check_window(window, period)
        self.service = service
        self.window, self.period = window, period
        self.members: dict[str, BatchMember] = {}
        self.batcher = Batcher(service.handle_batch, window, period, host_id, service.label)
        self._closed = False

    def member(self, key: str) -> BatchMember:
        self.members[key] = BatchMember(self, key)
        return self.members[key]

    def release(self, member: BatchMember) -> None:
        """A key stops being served; the last one closes the shared planner."""
        self.members.pop(member.key, None)
        if not self.members and not self._closed:
            self._closed = True
            self.batcher.close()
            self.service.close()


class BatchMember:
    """One key of a batch group, as the host serves it (a PlannerService)."""

    def __init__(self, group: BatchGroup, key: str) -> None:
        self.group, self.key = group, key
        self._last_cycle: _Cycle | None = None  # this key's latest cycle, maybe in a batch

    @property
    def owner(self) -> object:
        """What a reload acts on (SIGHUP reloads each owner once, not once per key)."""
        return self.group

    @property
    def plugin_type(self) -> PluginType:
        return self.group.service.plugin_type

    @property
    def isolation(self) -> str:
        return self.group.service.isolation

    @property
    def journal(self) -> Journal:
        return self.group.service.journal

    @property
    def swapped_at(self) -> float:
        return self.group.service.swapped_at

    @property
    def spec(self) -> PlannerSpec | None:
        spec = getattr(self.group.service, "spec", None)
        return spec if isinstance(spec, PlannerSpec) else None

    @property
    def label(self) -> str:
        return self.group.service.label

    @property
    def where(self) -> str:
        return self.group.service.where

    @property
    def batch(self) -> dict[str, object]:
        """What ``nav2-pyif hosts`` shows of the group."""
        batcher = self.group.batcher
        return {
            "keys": sorted(self.group.members),
            "window_s": self.group.window,
            "period_s": self.group.period,
            "batches": batcher.batches,
            "cycles": batcher.cycles,
            "dropped": batcher.dropped,
            "superseded": batcher.superseded,
        }

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        if key_op == CYCLE_OP:
            return self.group.batcher.submit(self.key, payload)
        self._after_last_cycle()
        return self.group.service.handle(payload, key_op)

    def submit_cycle(self, payload: bytes, answer: Answer) -> None:
        """A control cycle answered from its batch's thread; this key's next call of another
        op waits for it (a key's calls take effect in the order they came)."""
        self._last_cycle = self.group.batcher.submit_nowait(self.key, payload, answer)

    def _after_last_cycle(self) -> None:
        last = self._last_cycle
        if last is not None:
            last.done.wait()
            self._last_cycle = None

    def handle_batch(self, payloads: list[bytes]) -> list[bytes]:
        return self.group.service.handle_batch(payloads)

    def handle_cancel(self, payload: bytes) -> bytes:
        return self.group.service.handle_cancel(payload)

    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str:
        """A hot swap of the whole group: its keys share one planner."""
        message = self.group.service.reload(spec, allow_type_change=allow_type_change)
        return f"{message}; batch group of {len(self.group.members)} key(s)"

    def close(self) -> None:
        self.group.release(self)
