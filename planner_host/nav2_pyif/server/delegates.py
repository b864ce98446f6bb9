"""The function-delegate style: a module of plain functions plus a role map.

    planner-host --key nav2_pyif/robot1/FollowPath --module my_pkg.apf \\
        --delegate compute_velocity_commands=compute --delegate set_plan=set_plan

Without ``--delegate``, the module's functions named after the roles are bound (a module
defining ``compute_velocity_commands`` and ``set_plan`` needs no map). Each role left without a
function is logged as a warning saying what Nav2's call then does.

Signatures (a function that reads the costmap gets it as its first argument):
    compute_velocity_commands(costmap: Costmap, pose: PoseStamped, twist: Twist) -> TwistStamped
    set_plan(plan: Plan)                      # reads like nav_msgs/Path
    set_speed_limit(speed_limit: float, is_percentage: bool)
    create_plan(costmap: Costmap, start: PoseStamped, goal: PoseStamped) -> Path | Plan | array
    smooth(costmap: Costmap, path: Plan, max_time: float) -> Path | Plan | array
    is_goal_reached(pose: Pose, goal: Pose, velocity: Twist) -> bool
    get_tolerances() -> GoalChecker | None
    check(pose: PoseStamped) -> bool            # a progress checker
    update_costs(window: LayerWindow) -> uint8 array | (array, Combine)   # a costmap layer
    update_bounds(robot_x, robot_y, robot_yaw, bounds) -> bounds; match_size(size_x, size_y,
    resolution, origin_x, origin_y)
    configure(params: Parameters); activate(); deactivate(); cleanup(); reset(); cancel() -> bool
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

from nav2_pyif.controller import Controller
from nav2_pyif.costmap_layer import Bounds, CostmapLayer, LayerWindow
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.global_planner import GlobalPlanner
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.goal_checker_plugin import GoalCheckerPlugin
from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin
from nav2_pyif.progress_checker import ProgressCheckerPlugin
from nav2_pyif.roles import ALL_ROLES, KIND_ROLES, LIFECYCLE_ROLES, check_roles
from nav2_pyif.server.loader import import_module
from nav2_pyif.smoother import Smoother

#: What Nav2's call does when a role has no function (logged as a warning at load).
WITHOUT_DELEGATE = {
    "set_plan": "Nav2's global plan is kept in the controller's self.plan, but no function of "
    "yours receives it: compute_velocity_commands(costmap, pose, twist) has no plan to follow "
    "(delegate set_plan=FUNCTION(plan) and keep it, as nav2_pyif_planners.apf does)",
    "set_speed_limit": "Nav2's speed limits (speed filter zones) never reach your functions",
    "cancel": "a cancel is answered at once as done",
    "reset": "Nav2's reset between goals does nothing",
    "get_tolerances": "getTolerances reports no tolerances (returns false) to the controller",
    "update_bounds": "the costmap's update bounds are not grown: your costs reach only the "
    "cells other layers update",
    "match_size": "the master grid's size and origin are not passed on",
    "configure": "your functions get no Parameters: the plugin's parameters in the Nav2 YAML "
    "are not read",
    "activate": "Nav2's activate does nothing",
    "deactivate": "Nav2's deactivate does nothing",
    "cleanup": "Nav2's cleanup does nothing",
}

log = logging.getLogger("nav2_pyif.server.delegates")
P = TypeVar("P", bound=PlannerPlugin)


def delegate_class(
    module_name: str, delegates: Mapping[str, str], *, reload: bool = False, quiet: bool = False
) -> type[PlannerPlugin]:
    """Build a plugin class (a Controller, GlobalPlanner, Smoother, GoalCheckerPlugin or
    ProgressCheckerPlugin) whose methods call the module's functions:
    those ``delegates`` maps roles to, or (no map) those named after the roles. Logs a
    warning for each role left without a function, unless ``quiet`` (a worker restart)."""
    check_roles(delegates)
    module = import_module(module_name, reload=reload)
    if not delegates:
        delegates = {r: r for r in sorted(ALL_ROLES) if callable(getattr(module, r, None))}
        if not set(KIND_ROLES) & set(delegates):
            raise PlannerLoadError(
                f"module {module_name!r} defines none of compute_velocity_commands (a "
                "controller), create_plan (a global planner), smooth (a smoother), "
                "is_goal_reached (a goal checker), check (a progress checker) or update_costs "
                "(a costmap layer); name your functions after the roles or map them with "
                "--delegate ROLE=FUNCTION"
            )
        if not quiet:
            log.info("%s: functions bound by name: %s", module_name, ", ".join(delegates))
    kinds = sorted(set(KIND_ROLES) & set(delegates))
    if len(kinds) != 1:
        raise PlannerLoadError(
            "delegates need exactly one of compute_velocity_commands (a controller), "
            "create_plan (a global planner), smooth (a smoother), is_goal_reached (a goal "
            "checker), check (a progress checker) or update_costs (a costmap layer); got "
            f"{', '.join(kinds) or 'none'}"
        )
    kind = kinds[0]
    funcs: dict[str, Callable[..., Any]] = {}
    for role, func_name in delegates.items():
        func = getattr(module, func_name, None)
        if not callable(func):
            raise PlannerLoadError(
                f"module {module_name!r} has no function {func_name!r} (delegate for {role})"
            )
        funcs[role] = func
    roles = (KIND_ROLES[kind] - {kind}) | LIFECYCLE_ROLES
    # Nav2's checkers are only initialized (= configure): no warning for the other three.
    lifecycle = (
        {"configure"} if kind in ("is_goal_reached", "check", "update_costs") else LIFECYCLE_ROLES
    )
    for role in [] if quiet else sorted((roles & (lifecycle | KIND_ROLES[kind])) - set(funcs)):
        log.warning("%s: %s has no delegate: %s", module_name, role, WITHOUT_DELEGATE[role])
    stray = sorted(set(funcs) - roles - {kind})
    if stray:
        raise PlannerLoadError(
            f"delegates {', '.join(stray)} are not roles of a plugin whose main role is "
            f"{kind}; its roles: {', '.join(sorted(roles | {kind}))}"
        )
    build = {
        "compute_velocity_commands": _controller_class,
        "create_plan": _planner_class,
        "smooth": _smoother_class,
        "is_goal_reached": _goal_checker_class,
        "check": _progress_checker_class,
        "update_costs": _layer_class,
    }[kind]
    return build(module_name, funcs)


class _DelegateLifecycle(PlannerPlugin):
    """configure(params) / activate() / deactivate() / cleanup() delegates, when given."""

    _funcs: dict[str, Callable[..., Any]]

    def configure(self) -> None:
        if "configure" in self._funcs:
            self._funcs["configure"](self.params)

    def activate(self) -> None:
        if "activate" in self._funcs:
            self._funcs["activate"]()

    def deactivate(self) -> None:
        if "deactivate" in self._funcs:
            self._funcs["deactivate"]()

    def cleanup(self) -> None:
        if "cleanup" in self._funcs:
            self._funcs["cleanup"]()

    def reset(self) -> None:  # a role of controllers, checkers and layers; others never get it
        if "reset" in self._funcs:
            self._funcs["reset"]()


def _named(cls: type[P], module_name: str) -> type[P]:
    """Log and error messages name a delegate plugin after its module."""
    cls.__qualname__ = cls.__name__ = f"Delegates[{module_name}]"
    return cls


def _controller_class(module_name: str, funcs: dict[str, Callable[..., Any]]) -> type[Controller]:
    class DelegateController(_DelegateLifecycle, Controller):
        _funcs = funcs

        def set_plan(self, plan: Plan) -> None:
            super().set_plan(plan)
            if "set_plan" in funcs:
                funcs["set_plan"](plan)

        def compute_velocity_commands(
            self, pose: Any, velocity: Any, goal_checker: GoalChecker | None
        ) -> Any:
            return funcs["compute_velocity_commands"](self.costmap, pose, velocity)

        def set_speed_limit(self, speed_limit: float, percentage: bool) -> None:
            super().set_speed_limit(speed_limit, percentage)
            if "set_speed_limit" in funcs:
                funcs["set_speed_limit"](speed_limit, percentage)

        def cancel(self) -> bool:
            return bool(funcs["cancel"]()) if "cancel" in funcs else True

    return _named(DelegateController, module_name)


def _planner_class(module_name: str, funcs: dict[str, Callable[..., Any]]) -> type[GlobalPlanner]:
    class DelegatePlanner(_DelegateLifecycle, GlobalPlanner):
        _funcs = funcs

        def create_plan(self, start: Any, goal: Any, cancel_checker: Callable[[], bool]) -> Any:
            return funcs["create_plan"](self.costmap, start, goal)

    return _named(DelegatePlanner, module_name)


def _smoother_class(module_name: str, funcs: dict[str, Callable[..., Any]]) -> type[Smoother]:
    class DelegateSmoother(_DelegateLifecycle, Smoother):
        _funcs = funcs

        def smooth(self, path: Plan, max_time: float) -> Any:
            return funcs["smooth"](self.costmap, path, max_time)

    return _named(DelegateSmoother, module_name)


def _goal_checker_class(
    module_name: str, funcs: dict[str, Callable[..., Any]]
) -> type[GoalCheckerPlugin]:
    class DelegateGoalChecker(_DelegateLifecycle, GoalCheckerPlugin):
        _funcs = funcs

        def is_goal_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
            return funcs["is_goal_reached"](pose, goal, velocity)  # type: ignore[no-any-return]

        def get_tolerances(self) -> GoalChecker | None:
            return funcs["get_tolerances"]() if "get_tolerances" in funcs else None

    return _named(DelegateGoalChecker, module_name)


def _progress_checker_class(
    module_name: str, funcs: dict[str, Callable[..., Any]]
) -> type[ProgressCheckerPlugin]:
    class DelegateProgressChecker(_DelegateLifecycle, ProgressCheckerPlugin):
        _funcs = funcs

        def check(self, pose: Any) -> bool:
            return funcs["check"](pose)  # type: ignore[no-any-return]

    return _named(DelegateProgressChecker, module_name)


def _layer_class(module_name: str, funcs: dict[str, Callable[..., Any]]) -> type[CostmapLayer]:
    class DelegateLayer(_DelegateLifecycle, CostmapLayer):
        _funcs = funcs

        def update_costs(self, window: LayerWindow) -> Any:
            return funcs["update_costs"](window)

        def update_bounds(
            self, robot_x: float, robot_y: float, robot_yaw: float, bounds: Bounds
        ) -> Bounds:
            if "update_bounds" not in funcs:
                return bounds
            return funcs["update_bounds"](robot_x, robot_y, robot_yaw, bounds)  # type: ignore[no-any-return]

        def match_size(
            self, size_x: int, size_y: int, resolution: float, origin_x: float, origin_y: float
        ) -> None:
            super().match_size(size_x, size_y, resolution, origin_x, origin_y)
            if "match_size" in funcs:
                funcs["match_size"](size_x, size_y, resolution, origin_x, origin_y)

    return _named(DelegateLayer, module_name)
