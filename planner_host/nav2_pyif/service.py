"""What the Zenoh side of the host needs from a served planner, and the in-process variant
(``--isolation none``: fastest, but a crashing planner takes the host down with it)."""

from __future__ import annotations

import logging
from typing import Protocol

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.runtime import PlannerRuntime
from nav2_pyif.spec import PlannerSpec

log = logging.getLogger("nav2_pyif.host")


class PlannerService(Protocol):
    plugin_type: PluginType

    @property
    def label(self) -> str: ...

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes: ...

    def handle_cancel(self, payload: bytes) -> bytes: ...

    def reload(self, spec: PlannerSpec | None = None) -> str: ...

    def close(self) -> None: ...


class InProcessPlanner:
    """A PlannerRuntime in the host process. Reload re-imports the module in place and drops
    the sessions: each plugin then gets SessionUnknown once and re-sends its state."""

    def __init__(self, spec: PlannerSpec, host_id: str) -> None:
        self.spec = spec
        self.host_id = host_id
        self.runtime = PlannerRuntime(spec.load(), host_id, label=spec.describe())
        self.plugin_type = self.runtime.plugin_type

    @property
    def label(self) -> str:
        return self.runtime.label

    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        return self.runtime.handle(payload, key_op)

    def handle_cancel(self, payload: bytes) -> bytes:
        return self.runtime.handle_cancel(payload)

    def reload(self, spec: PlannerSpec | None = None) -> str:
        new_spec = spec or self.spec
        runtime = PlannerRuntime(
            new_spec.load(reload=True), self.host_id, label=new_spec.describe()
        )
        old, self.runtime, self.spec = self.runtime, runtime, new_spec
        self.plugin_type = runtime.plugin_type
        old.close()
        return f"{new_spec.key}: now serving {new_spec.describe()} in process (sessions reset)"

    def close(self) -> None:
        self.runtime.close()
