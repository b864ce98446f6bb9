"""A served planner whose calls are recorded: the host serves it as it would the planner."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.server.batch_runtime import CYCLE_OP
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.recording.recorder import Recorder

if TYPE_CHECKING:
    from nav2_pyif.server.recording.live import LiveTap
from nav2_pyif.server.service import PlannerService
from nav2_pyif.server.spec import PlannerSpec


class RecordedService:
    """Wraps a PlannerService: each call's request, reply and times go to the recorder.

    Everything else (a batch group's ``owner``, ``batch``, ``spec``) is the wrapped one's, so
    the host treats it as it treats that service; a batched cycle (``submit_cycle``) is
    recorded when its batch answers it."""

    def __init__(self, inner: PlannerService, key: str, recorder: Recorder | LiveTap) -> None:
        self.inner, self.key = inner, key
        # --record and nav2-pyif record (a LiveTap) both: one wrapper, so both get the same
        # times of each call
        self.recorders: list[Recorder | LiveTap] = [recorder]

    def _add(self, op: str, payload: bytes, reply: bytes, t0: int, t1: int) -> None:
        for recorder in self.recorders:
            recorder.add(self.key, op, payload, reply, t0, t1)

    @property
    def plugin_type(self) -> PluginType:
        return self.inner.plugin_type

    @property
    def isolation(self) -> str:
        return self.inner.isolation

    @property
    def journal(self) -> Journal:
        return self.inner.journal

    @property
    def swapped_at(self) -> float:
        return self.inner.swapped_at

    @property
    def label(self) -> str:
        return self.inner.label

    @property
    def where(self) -> str:
        return self.inner.where

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        t0 = time.time_ns()
        reply = self.inner.handle(payload, key_op)
        if key_op is not None:
            self._add(key_op, payload, reply, t0, time.time_ns())
        return reply

    def handle_cancel(self, payload: bytes) -> bytes:
        return self.inner.handle_cancel(payload)

    def handle_batch(self, payloads: list[bytes]) -> list[bytes]:
        t0 = time.time_ns()
        replies = self.inner.handle_batch(payloads)
        t1 = time.time_ns()
        for payload, reply in zip(payloads, replies, strict=True):
            self._add(CYCLE_OP, payload, reply, t0, t1)
        return replies

    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str:
        message = self.inner.reload(spec, allow_type_change)
        for recorder in self.recorders:
            recorder.reloaded(self.key, self.inner.label)
        return message

    def close(self) -> None:
        self.inner.close()

    def __getattr__(self, name: str) -> Any:
        found = getattr(self.inner, name)  # AttributeError when the inner one has none
        if name != "submit_cycle":
            return found
        submit: Callable[[bytes, Callable[[bytes], None]], None] = found

        def submit_recorded(payload: bytes, answer: Callable[[bytes], None]) -> None:
            t0 = time.time_ns()

            def answered(reply: bytes) -> None:
                self._add(CYCLE_OP, payload, reply, t0, time.time_ns())
                answer(reply)

            submit(payload, answered)

        return submit_recorded


def recorded(
    services: list[PlannerService], keys: list[str], recorder: Recorder | LiveTap
) -> list[Any]:
    """``services`` (one per key, in order), those of the recorder's keys wrapped (or, when
    already wrapped for another recorder, recorded by this one too)."""
    out: list[Any] = []
    for service, key in zip(services, keys, strict=True):
        if key in recorder.keys and isinstance(service, RecordedService):
            service.recorders.append(recorder)
        elif key in recorder.keys:
            service = RecordedService(service, key, recorder)
        out.append(service)
    return out
