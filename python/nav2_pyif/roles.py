"""The roles of the function-delegate style (``planner-host --module M --delegate
ROLE=FUNCTION``): which plugin method each module function stands for. The planner host binds
them (nav2_pyif.server.delegates); ``nav2-pyif reload --delegate`` checks them too."""

from __future__ import annotations

import difflib
from collections.abc import Mapping

from nav2_pyif.exceptions import PlannerLoadError

CONTROLLER_ROLES = frozenset(
    {"compute_velocity_commands", "set_plan", "set_speed_limit", "cancel", "reset"}
)
PLANNER_ROLES = frozenset({"create_plan"})
SMOOTHER_ROLES = frozenset({"smooth"})
GOAL_CHECKER_ROLES = frozenset({"is_goal_reached", "get_tolerances", "reset"})
PROGRESS_CHECKER_ROLES = frozenset({"check", "reset"})
LAYER_ROLES = frozenset({"update_costs", "update_bounds", "match_size", "reset"})
LIFECYCLE_ROLES = frozenset({"configure", "activate", "deactivate", "cleanup"})
#: The role whose function makes a module a plugin of that kind -> the kind's other roles.
KIND_ROLES = {
    "compute_velocity_commands": CONTROLLER_ROLES,
    "create_plan": PLANNER_ROLES,
    "smooth": SMOOTHER_ROLES,
    "is_goal_reached": GOAL_CHECKER_ROLES,
    "check": PROGRESS_CHECKER_ROLES,
    "update_costs": LAYER_ROLES,
}
ALL_ROLES = frozenset().union(*KIND_ROLES.values()) | LIFECYCLE_ROLES


def check_roles(delegates: Mapping[str, str]) -> None:
    """Refuse unknown roles, naming the closest known one and every valid role."""
    for role in sorted(set(delegates) - ALL_ROLES):
        close = difflib.get_close_matches(role, ALL_ROLES, n=1)
        raise PlannerLoadError(
            f"unknown delegate role {role!r}"
            + (f" (did you mean {close[0]}?)" if close else "")
            + f"; roles: {', '.join(sorted(ALL_ROLES))}"
        )


def parse_delegates(items: list[str]) -> dict[str, str]:
    """["role=function", "role2=function2,role3=f3", "role4"] -> {role: function}, roles
    checked; a bare role is the function of its name, and a role given twice keeps the last."""
    out: dict[str, str] = {}
    for item in items:
        for pair in filter(None, (p.strip() for p in item.split(","))):
            role, sep, func = pair.partition("=")
            role, func = role.strip(), func.strip() if sep else role.strip()
            if not role or not func:
                raise PlannerLoadError(f"delegate {pair!r} is not of the form role=function")
            out[role] = func
    check_roles(out)
    return out
