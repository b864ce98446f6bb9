"""Which planner to serve: a class spec or a module with delegates. Picklable, so it can be
sent to a worker process, and loadable there."""

from __future__ import annotations

from dataclasses import dataclass, field

from nav2_pyif.plugin import PlannerPlugin


@dataclass(frozen=True)
class PlannerSpec:
    key: str
    planner: str | None = None  # package.module:Class
    module: str | None = None  # function-delegate style
    delegates: dict[str, str] = field(default_factory=dict)
    # the main role it is served as (compute_velocity_commands, create_plan, ...) when the
    # caller knows it (the runner's --controller, --planner): binds ``module:function``
    kind: str | None = None
    # served in a batch group (planner-host --batch): not part of what is served, so a
    # reload's "same planner?" comparison ignores it
    batch: bool = field(default=False, compare=False)

    def load(self, *, reload: bool = False, quiet: bool = False) -> type[PlannerPlugin]:
        """The planner class; ``quiet``: no load-time messages (a worker restart)."""
        from nav2_pyif.server.delegates import delegate_class
        from nav2_pyif.server.loader import load_class

        if self.planner:
            return load_class(self.planner, kind=self.kind, reload=reload, quiet=quiet)
        assert self.module is not None
        return delegate_class(
            self.module, self.delegates, kind=self.kind, reload=reload, quiet=quiet
        )

    def describe(self) -> str:
        return self.planner or f"{self.module} (delegates)"

    def with_planner(
        self, planner: str | None, module: str | None, delegates: dict[str, str] | None
    ) -> PlannerSpec:
        """The same key with another planner (hot swap); None keeps the current one."""
        if planner is None and module is None:
            return self
        return PlannerSpec(
            self.key, planner, module, dict(delegates or {}), self.kind, batch=self.batch
        )
