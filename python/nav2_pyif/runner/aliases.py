"""Short names the runner accepts for planners: those the installed distributions declare as
entry points in the group ``nav2_pyif.planners`` (the reference planners, nav2-pyif-planners,
declare theirs in planners/setup.py), name -> import path (``module:Class``, or a module of
function delegates). Only their import paths: the runner never imports a planner; the planner
host it starts does."""

from __future__ import annotations

from importlib.metadata import entry_points

#: The entry point group a distribution declares its planners' short names in.
GROUP = "nav2_pyif.planners"
#: What to install when none is declared.
INSTALL_HINT = "the reference planners: pip install ./planners in a clone (nav2-pyif-planners)"


def planner_aliases() -> dict[str, str]:
    """name -> import path, of every planner an installed distribution declares, by name."""
    return {point.name: point.value for point in sorted(entry_points(group=GROUP))}
