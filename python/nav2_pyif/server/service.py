"""What the Zenoh side of the host needs from a served planner, and the in-process variant
(``--isolation none``: fastest, but a crashing planner takes the host down with it)."""

from __future__ import annotations

import logging
import threading
import time
from typing import Protocol

import msgpack
from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.batch_runtime import CYCLE_OP, handle_batch
from nav2_pyif.server.journal import Journal
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif.server.spec import PlannerSpec

log = logging.getLogger("nav2_pyif.server.host")


class PlannerService(Protocol):
    # read-only here: a batch group's keys read them from the planner they share
    @property
    def plugin_type(self) -> PluginType: ...

    @property
    def isolation(self) -> str: ...  # "process" or "none", as planner-host --isolation says

    @property
    def journal(self) -> Journal: ...  # every live session, len() of it their number

    @property
    def swapped_at(self) -> float: ...  # unix time of the last hot swap (0: none yet)

    @property
    def label(self) -> str: ...

    @property
    def where(self) -> str: ...  # where the planner runs: "worker 1234", "in process"

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes: ...

    def handle_cancel(self, payload: bytes) -> bytes: ...

    def handle_batch(self, payloads: list[bytes]) -> list[bytes]: ...  # control cycles

    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str: ...

    def close(self) -> None: ...


class InProcessPlanner:
    """A PlannerRuntime in the host process. Reload re-imports the module in place and, as
    the supervised variant does, replays every live session (from a journal) on the new
    planner before swapping: all or nothing."""

    isolation = "none"

    def __init__(self, spec: PlannerSpec, host_id: str) -> None:
        self.spec = spec
        self.host_id = host_id
        self.runtime = PlannerRuntime(spec.load(), host_id, label=spec.describe())
        self.plugin_type = self.runtime.plugin_type
        self.journal = Journal()
        self.swapped_at = 0.0
        self._lock = threading.Lock()  # calls vs. the swap

    @property
    def label(self) -> str:
        return self.runtime.label

    where = "in process"

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        with self._lock:
            reply = self.runtime.handle(payload, key_op)
            if key_op is not None:
                self.journal.note(key_op, payload, reply)
            return reply

    def handle_cancel(self, payload: bytes) -> bytes:
        return self.runtime.handle_cancel(payload)

    def handle_batch(self, payloads: list[bytes]) -> list[bytes]:
        with self._lock:
            replies: list[bytes] = msgpack.unpackb(
                handle_batch(self.runtime, msgpack.packb(payloads))
            )
            for payload, reply in zip(payloads, replies, strict=True):
                self.journal.note(CYCLE_OP, payload, reply)
            return replies

    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str:
        new_spec = spec or self.spec
        try:
            runtime = PlannerRuntime(
                new_spec.load(reload=True), self.host_id, label=new_spec.describe()
            )
        except PlannerLoadError as exc:
            raise self._refused(exc) from exc
        old = self.runtime
        # Delegates keep their state in their module, re-imported in place and so shared by
        # both versions: a discarded version's cleanup would reset the other's state.
        shared = self.spec.module is not None and self.spec.module == new_spec.module

        def swap() -> None:  # called with the lock held, between two calls
            self.runtime, self.spec, self.plugin_type = runtime, new_spec, runtime.plugin_type
            self.swapped_at = time.time()

        try:
            carried = self.journal.hand_over(
                lambda op, payload: runtime.handle(payload, op),
                (new_spec.describe(), runtime.plugin_type),
                self.plugin_type,
                self._lock,
                swap,
                allow_type_change,
            )
        except PlannerLoadError as exc:
            _discard(runtime, shared)
            raise self._refused(exc) from exc
        _discard(old, shared)
        return (
            f"{new_spec.key}: now serving {new_spec.describe()} in process "
            f"({carried} session(s) carried over)"
        )

    def _refused(self, exc: PlannerLoadError) -> PlannerLoadError:
        return PlannerLoadError(f"reload refused, still serving {self.label}: {exc}")

    def close(self) -> None:
        self.runtime.close()


def _discard(runtime: PlannerRuntime, shared_module: bool) -> None:
    """Close a runtime a swap left behind; without cleaning its sessions up when its planner
    shares module state with the one that stays."""
    if shared_module:
        runtime.sessions.clear()
    runtime.close()
