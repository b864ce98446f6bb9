"""The function-delegate style: a module of plain functions plus a role map.

    planner-host --key nav2_pyif/robot1/FollowPath --module my_pkg.apf \\
        --delegate compute_velocity_commands=compute --delegate set_plan=set_plan

Without ``--delegate``, the module's functions named after the roles are bound (a module
defining ``compute_velocity_commands`` and ``set_plan`` needs no map). Each role left without a
function is logged as a warning saying what Nav2's call then does.

``module:function`` (``nav2-pyif sim --controller my_pkg.ctl:steer``) binds ``function`` to
the main role of the plugin kind it is served as, and the module's other functions named after
that kind's roles.

Signatures (a function that reads the costmap gets it as its first argument):
    compute_velocity_commands(costmap: Costmap, pose: PoseStamped, twist: Twist) -> TwistStamped
    set_plan(plan: Plan)                      # reads like nav_msgs/Path
    set_speed_limit(speed_limit: float, is_percentage: bool)
    create_plan(costmap: Costmap, start: PoseStamped, goal: PoseStamped) -> Path | Plan | array
    smooth(costmap: Costmap, path: Plan, max_time: float) -> Path | Plan | array
    is_goal_reached(pose: Pose, goal: Pose, velocity: Twist) -> bool
    get_tolerances() -> GoalTolerances | None
    check(pose: PoseStamped) -> bool            # a progress checker
    update_costs(window: LayerWindow) -> uint8 array | (array, Combine)   # a costmap layer
    update_bounds(robot_x, robot_y, robot_yaw, bounds) -> bounds; match_size(size_x, size_y,
    resolution, origin_x, origin_y)
    configure(params: Parameters); activate(); deactivate(); cleanup(); reset(); cancel() -> bool

Keyword arguments a function gets when its signature names them (or takes ``**kwargs``):
    compute_velocity_commands: goal_checker (GoalTolerances: the goal's tolerances, or None),
        plan (the latest Plan, or None: no set_plan function needed), control_period
        ([s] the controller server's period, 1 / controller_frequency, or None)
    create_plan: cancel_checker (a callable returning True once Nav2 cancels)
"""

from __future__ import annotations

import inspect
import logging
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

from nav2_pyif.controller import Controller
from nav2_pyif.costmap_layer import Bounds, CostmapLayer, LayerWindow
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.global_planner import GlobalPlanner
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin
from nav2_pyif.progress_checker import ProgressChecker
from nav2_pyif.roles import ALL_ROLES, KIND_ROLES, LIFECYCLE_ROLES, check_roles
from nav2_pyif.server.loader import import_module
from nav2_pyif.smoother import Smoother

#: What Nav2's call does when a role has no function (logged as a warning at load).
WITHOUT_DELEGATE = {
    "set_plan": "Nav2's global plan reaches your functions only as compute_velocity_commands' "
    "plan= keyword argument (or delegate set_plan=FUNCTION(plan) and keep it, as "
    "nav2_pyif_planners.apf does)",
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
    module_name: str,
    delegates: Mapping[str, str],
    *,
    kind: str | None = None,
    reload: bool = False,
    quiet: bool = False,
) -> type[PlannerPlugin]:
    """Build a plugin class (a Controller, GlobalPlanner, Smoother, GoalChecker,
    ProgressChecker or CostmapLayer) whose methods call the module's functions:
    those ``delegates`` maps roles to, or (no map) those named after the roles. ``kind``: the
    main role it is served as (``compute_velocity_commands`` for a controller, ...), when the
    caller knows it: the module must be of that kind. Logs, at INFO, what it bound and each
    role left to its default, unless ``quiet`` (a worker restart)."""
    check_roles(delegates)
    if kind is not None and kind not in KIND_ROLES:
        raise PlannerLoadError(f"{kind!r} is not a main role; main roles: {', '.join(KIND_ROLES)}")
    module = import_module(module_name, reload=reload)
    if not delegates:
        named = KIND_ROLES[kind] | LIFECYCLE_ROLES if kind else ALL_ROLES
        delegates = {r: r for r in sorted(named) if callable(getattr(module, r, None))}
        if not set(KIND_ROLES) & set(delegates):
            raise PlannerLoadError(
                f"module {module_name!r} defines "
                + (
                    f"no function {kind}"
                    if kind
                    else "none of compute_velocity_commands (a controller), create_plan (a "
                    "global planner), smooth (a smoother), is_goal_reached (a goal checker), "
                    "check (a progress checker) or update_costs (a costmap layer)"
                )
                + "; name your functions after the roles, map them with --delegate "
                "ROLE=FUNCTION, or name the main one as module:function"
            )
        if not quiet:
            log.info("%s: functions bound by name: %s", module_name, ", ".join(delegates))
    return _bind(module_name, module, dict(delegates), kind, quiet)


def function_class(
    module_name: str, function: str, kind: str | None, *, reload: bool = False, quiet: bool = False
) -> type[PlannerPlugin]:
    """``module:function``: ``function`` as the main role ``kind`` (by default the role it is
    named after), the module's other functions named after that kind's roles beside it."""
    kind = kind or (function if function in KIND_ROLES else None)
    if kind is None:
        raise PlannerLoadError(
            f"{module_name}:{function} is a function, but which role it plays is not known: "
            f"serve it as a controller or a planner (nav2-pyif sim --controller / --planner), "
            f"or with planner-host --module {module_name} --delegate ROLE={function} (main "
            f"roles: {', '.join(KIND_ROLES)})"
        )
    module = import_module(module_name, reload=reload)
    roles = (KIND_ROLES[kind] - {kind}) | LIFECYCLE_ROLES
    delegates = {r: r for r in sorted(roles) if callable(getattr(module, r, None))}
    delegates[kind] = function
    if not quiet:
        others = ", ".join(sorted(set(delegates) - {kind}))
        log.info(
            "%s: %s bound to %s%s", module_name, function, kind, others and f"; by name: {others}"
        )
    return _bind(module_name, module, delegates, kind, quiet)


def _bind(
    module_name: str, module: Any, delegates: dict[str, str], kind: str | None, quiet: bool
) -> type[PlannerPlugin]:
    kinds = sorted(set(KIND_ROLES) & set(delegates))
    if len(kinds) != 1:
        raise PlannerLoadError(
            "delegates need exactly one of compute_velocity_commands (a controller), "
            "create_plan (a global planner), smooth (a smoother), is_goal_reached (a goal "
            "checker), check (a progress checker) or update_costs (a costmap layer); got "
            f"{', '.join(kinds) or 'none'}"
        )
    if kind is not None and kinds[0] != kind:
        raise PlannerLoadError(
            f"module {module_name!r} has {kinds[0]}, not {kind}: it is served where a plugin "
            f"with {kind} is wanted"
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
    stray = sorted(set(funcs) - roles - {kind})
    if stray:
        raise PlannerLoadError(
            f"delegates {', '.join(stray)} are not roles of a plugin whose main role is "
            f"{kind}; its roles: {', '.join(sorted(roles | {kind}))}"
        )
    # Nav2's checkers and layers are only initialized (= configure): no word on the other three.
    lifecycle = (
        {"configure"} if kind in ("is_goal_reached", "check", "update_costs") else LIFECYCLE_ROLES
    )
    unbound = sorted((roles & (lifecycle | KIND_ROLES[kind])) - set(funcs))
    if kind == "compute_velocity_commands" and "plan" in _keywords(funcs[kind], {"plan"}):
        unbound = [r for r in unbound if r != "set_plan"]  # it gets the plan as plan=
    if unbound and not quiet:
        # INFO, not WARNING: leaving a role to Nav2's default is the style's point
        log.info(
            "%s: roles left to their default: %s",
            module_name,
            "; ".join(f"{role} has no delegate: {WITHOUT_DELEGATE[role]}" for role in unbound),
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


def _keywords(func: Callable[..., Any], offered: set[str]) -> set[str]:
    """Which of the ``offered`` keyword arguments ``func`` takes (all with ``**kwargs``)."""
    try:
        parameters = inspect.signature(func).parameters.values()
    except (TypeError, ValueError):  # a builtin or C function without a signature
        return set()
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters):
        return set(offered)
    return {
        p.name
        for p in parameters
        if p.name in offered
        and p.kind in (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    }


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
    compute = funcs["compute_velocity_commands"]
    keywords = _keywords(compute, {"goal_checker", "plan", "control_period"})

    class DelegateController(_DelegateLifecycle, Controller):
        _funcs = funcs

        def set_plan(self, plan: Plan) -> None:
            super().set_plan(plan)
            if "set_plan" in funcs:
                funcs["set_plan"](plan)

        def compute_velocity_commands(
            self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
        ) -> Any:
            offered = {
                "goal_checker": goal_checker,
                "plan": self.plan,
                "control_period": self.control_period,
            }
            extra = {name: offered[name] for name in keywords}
            return compute(self.costmap, pose, velocity, **extra)

        def set_speed_limit(self, speed_limit: float, percentage: bool) -> None:
            super().set_speed_limit(speed_limit, percentage)
            if "set_speed_limit" in funcs:
                funcs["set_speed_limit"](speed_limit, percentage)

        def cancel(self) -> bool:
            return bool(funcs["cancel"]()) if "cancel" in funcs else True

    return _named(DelegateController, module_name)


def _planner_class(module_name: str, funcs: dict[str, Callable[..., Any]]) -> type[GlobalPlanner]:
    create = funcs["create_plan"]
    wants_cancel = "cancel_checker" in _keywords(create, {"cancel_checker"})

    class DelegatePlanner(_DelegateLifecycle, GlobalPlanner):
        _funcs = funcs

        def create_plan(self, start: Any, goal: Any, cancel_checker: Callable[[], bool]) -> Any:
            if wants_cancel:
                return create(self.costmap, start, goal, cancel_checker=cancel_checker)
            return create(self.costmap, start, goal)

    return _named(DelegatePlanner, module_name)


def _smoother_class(module_name: str, funcs: dict[str, Callable[..., Any]]) -> type[Smoother]:
    class DelegateSmoother(_DelegateLifecycle, Smoother):
        _funcs = funcs

        def smooth(self, path: Plan, max_time: float) -> Any:
            return funcs["smooth"](self.costmap, path, max_time)

    return _named(DelegateSmoother, module_name)


def _goal_checker_class(
    module_name: str, funcs: dict[str, Callable[..., Any]]
) -> type[GoalChecker]:
    class DelegateGoalChecker(_DelegateLifecycle, GoalChecker):
        _funcs = funcs

        def is_goal_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
            return funcs["is_goal_reached"](pose, goal, velocity)  # type: ignore[no-any-return]

        def get_tolerances(self) -> GoalTolerances | None:
            return funcs["get_tolerances"]() if "get_tolerances" in funcs else None

    return _named(DelegateGoalChecker, module_name)


def _progress_checker_class(
    module_name: str, funcs: dict[str, Callable[..., Any]]
) -> type[ProgressChecker]:
    class DelegateProgressChecker(_DelegateLifecycle, ProgressChecker):
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
