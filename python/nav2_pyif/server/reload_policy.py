"""Which remote hot swaps (``nav2-pyif reload``, the ``P/admin/reload`` query) a host accepts.

A reload makes the host import code, so anyone who can send one on the network could make it
run any importable module. By default a host refuses them all; ``--allow-remote-reload``
accepts a fresh import of the planner it serves, and ``--reload-allow PATTERN`` (repeatable,
shell-style as fnmatch) the other planners it may load: a pattern matches ``module:Class``
or the module alone (``my_planners.*``, ``my_pkg.ctrl:Fast*``). SIGHUP is local and always
reloads. Zenoh's access control decides *who* may send a reload (the deployment guide); this
decides *what* a reload may load, whoever sent it.
"""

from __future__ import annotations

import fnmatch
from dataclasses import dataclass

from nav2_pyif.server.spec import PlannerSpec


@dataclass(frozen=True)
class ReloadPolicy:
    allow_remote: bool = False
    patterns: tuple[str, ...] = ()

    def refusal(self, requested: PlannerSpec | None) -> str | None:
        """Why a remote reload to ``requested`` is refused (None: a fresh import of the
        planner the key serves); None when it is allowed."""
        if not self.allow_remote:
            return (
                "remote reloads are off on this host (start planner-host with "
                "--allow-remote-reload, and --reload-allow PATTERN for other planners; "
                "SIGHUP on its machine reloads every planner)"
            )
        if requested is None:
            return None
        names = _names(requested)
        if any(fnmatch.fnmatchcase(n, p) for n in names for p in self.patterns):
            return None
        allowed = ", ".join(self.patterns) or "none: only a fresh import of the current planner"
        return (
            f"{requested.describe()} is not in this host's reload allow-list "
            f"(--reload-allow: {allowed})"
        )


def _names(spec: PlannerSpec) -> list[str]:
    """What a pattern may match: ``module:Class`` and ``module``, or the delegates' module."""
    if spec.planner:
        return [spec.planner, spec.planner.partition(":")[0]]
    return [spec.module or ""]
