"""Check what a planner returned before it goes back to Nav2: right type, finite numbers."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from geometry_msgs.msg import Twist, TwistStamped

from nav2_pyif._messages import stamp_to_ns, twist_to_list
from nav2_pyif.behavior import Failure, Status, Step
from nav2_pyif.costmap_layer import Combine
from nav2_pyif.exceptions import (
    ControllerException,
    FailedToSmoothPath,
    InvalidPath,
    Nav2Error,
    NoValidControl,
    NoValidPathCouldBeFound,
    PlannerException,
    SmootherException,
)
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.plan import Plan

TWIST_FIELDS = ("linear.x", "linear.y", "linear.z", "angular.x", "angular.y", "angular.z")


def checked_twist_stamped(result: Any, method: str) -> list[float]:
    """The 6 components of ``result`` if it is a TwistStamped and they are finite; else a
    typed error."""
    if not isinstance(result, TwistStamped):
        hint = (
            " — wrap it: TwistStamped(header=pose.header, twist=your_twist)"
            if isinstance(result, Twist)
            else ""
        )
        raise ControllerException(
            f"{method} returned {type(result).__name__}; expected "
            f"geometry_msgs.msg.TwistStamped{hint}"
        )
    if not isinstance(result.header.frame_id, str):
        raise ControllerException(f"{method} returned a TwistStamped whose frame_id is not a str")
    values = twist_to_list(result.twist)
    if all(map(math.isfinite, values)):  # the every-cycle case, without building names
        return values
    bad = [f"{n}={v}" for n, v in zip(TWIST_FIELDS, values, strict=False) if not math.isfinite(v)]
    if bad:
        raise NoValidControl(f"{method} returned a non-finite velocity: {', '.join(bad)}")
    return values


def checked_plan(
    result: Any,
    frame_id: str,
    stamp_ns: int,
    method: str,
    errors: tuple[type[Nav2Error], type[Nav2Error]] = (PlannerException, NoValidPathCouldBeFound),
) -> Plan:
    """A Plan from what create_plan returned (Plan, nav_msgs/Path or array); finite values.
    ``errors``: what to raise for a wrong type and for non-finite values."""
    wrong_type, not_finite = errors
    if isinstance(result, Plan):
        plan = result
    elif isinstance(result, np.ndarray):
        if result.ndim != 2 or result.shape[1] not in (2, 3, 7):
            raise wrong_type(
                f"{method} returned an array of shape {result.shape}; expected (N, 2) x, y, "
                f"(N, 3) x, y, yaw or (N, 7) x, y, z, qx, qy, qz, qw"
            )
        plan = Plan(result, frame_id, stamp_ns)
    elif hasattr(result, "poses") and hasattr(result, "header"):
        plan = Plan.from_msg(result)
    else:
        raise wrong_type(
            f"{method} returned {type(result).__name__}; expected nav_msgs.msg.Path, "
            f"nav2_pyif.Plan or a NumPy array"
        )
    finite = np.isfinite(plan.array)
    if not finite.all():
        rows = int((~finite.all(axis=1)).sum())
        raise not_finite(
            f"{method} returned a path with non-finite values in {rows} of {len(plan)} poses"
        )
    return plan


def checked_bool(result: Any, method: str, error: type[Nav2Error]) -> bool:
    if not isinstance(result, (bool, np.bool_)):
        raise error(f"{method} returned {type(result).__name__}; expected bool")
    return bool(result)


def checked_segment(result: Any, plan_length: int) -> tuple[int, int]:
    """What find_plan_segment returned -> (start, end) with 0 <= start < end <= plan_length;
    else InvalidPath (Nav2's FeasiblePathHandler throws it for an empty transformed plan)."""
    if not (isinstance(result, (tuple, list)) and len(result) == 2):
        raise InvalidPath(
            f"find_plan_segment returned {type(result).__name__}; expected (start, end)"
        )
    if not all(isinstance(i, (int, np.integer)) and not isinstance(i, bool) for i in result):
        kinds = ", ".join(type(i).__name__ for i in result)
        raise InvalidPath(f"find_plan_segment returned ({kinds}); expected two ints")
    start, end = int(result[0]), int(result[1])
    if not 0 <= start < end <= plan_length:
        raise InvalidPath(
            f"find_plan_segment returned ({start}, {end}): not a segment of the plan's "
            f"{plan_length} poses (0 <= start < end <= {plan_length})"
        )
    return start, end


def checked_smoothed(result: Any, frame_id: str, stamp_ns: int) -> tuple[Plan, bool]:
    """What smooth returned (a path, or ``(path, was_completed)``) -> a finite Plan and
    was_completed; the input path's frame and stamp for an array."""
    completed: Any = True
    if isinstance(result, tuple) and len(result) == 2:
        result, completed = result
    plan = checked_plan(
        result, frame_id, stamp_ns, "smooth", (SmootherException, FailedToSmoothPath)
    )
    return plan, checked_bool(completed, "smooth's was_completed", SmootherException)


def tolerances_to_wire(tolerances: Any) -> dict[str, Any]:
    """get_tolerances' GoalTolerances (or None) -> the reply body, as Nav2's goal checkers fill
    getTolerances: position x, y = the xy tolerance, the yaw tolerance as a quaternion about
    z, linear x, y = the translational and angular z = the rotational stopped velocity."""
    if tolerances is None:
        return {
            "available": False,
            "pose_tolerance": [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            "velocity_tolerance": [0.0] * 6,
        }
    if not isinstance(tolerances, GoalTolerances):
        raise ControllerException(
            f"get_tolerances returned {type(tolerances).__name__}; expected "
            "nav2_pyif.GoalTolerances or None"
        )
    xy, yaw = float(tolerances.xy_goal_tolerance), float(tolerances.yaw_goal_tolerance)
    trans = float(tolerances.trans_stopped_velocity)
    rot = float(tolerances.rot_stopped_velocity)
    values = [xy, yaw, trans, rot]
    if not all(math.isfinite(v) for v in values):
        raise ControllerException(f"get_tolerances returned non-finite values: {values}")
    body: dict[str, Any] = {
        "available": True,
        "pose_tolerance": [xy, xy, 0.0, 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)],
        "velocity_tolerance": [trans, trans, 0.0, 0.0, 0.0, rot],
    }
    if tolerances.path_length_tolerance is not None:  # Lyrical's getTolerances' third value
        path_length = float(tolerances.path_length_tolerance)
        if not math.isfinite(path_length):
            raise ControllerException(
                f"get_tolerances returned a non-finite path_length_tolerance: {path_length}"
            )
        body["path_length_tolerance"] = path_length
    return body


def checked_bounds(result: Any) -> tuple[float, float, float, float]:
    """update_bounds' (min_x, min_y, max_x, max_y): four numbers, none NaN (infinite is what
    Nav2 starts from: no bounds yet)."""
    try:
        values = tuple(float(v) for v in result)
    except (TypeError, ValueError):
        values = ()
    if len(values) != 4 or any(math.isnan(v) for v in values):
        raise ControllerException(
            f"update_bounds returned {result!r}; expected (min_x, min_y, max_x, max_y) [m]"
        )
    return values  # type: ignore[return-value]


def checked_layer_costs(result: Any, shape: tuple[int, int]) -> tuple[bytes, str]:
    """update_costs' costs (and combine mode) -> the window's bytes and the mode's name."""
    combine: Any = Combine.MAX
    if isinstance(result, tuple) and len(result) == 2:
        result, combine = result
    try:
        mode = Combine(combine)
    except ValueError:
        modes = ", ".join(m.value for m in Combine)
        raise ControllerException(
            f"update_costs returned the combine mode {combine!r}; expected one of {modes}"
        ) from None
    if not isinstance(result, np.ndarray) or result.dtype != np.uint8 or result.shape != shape:
        got = (
            f"a {result.dtype} array of shape {result.shape}"
            if isinstance(result, np.ndarray)
            else type(result).__name__
        )
        raise ControllerException(
            f"update_costs returned {got}; expected a uint8 array of the window's shape {shape}"
        )
    return np.ascontiguousarray(result).tobytes(), mode.value


def checked_step(result: Any, method: str, frame_id: str) -> dict[str, Any]:
    """A behaviour's answer (a Step, a Status, ``(Status, TwistStamped | None)`` or, from
    on_run, ``(Status, Failure)``) as its reply body: a known status, finite command."""
    if isinstance(result, tuple) and len(result) == 2 and isinstance(result[1], Failure | str):
        step = Step(Status(result[0]), None, Failure(result[1]))
    elif isinstance(result, tuple) and len(result) == 2:
        step = Step(Status(result[0]), result[1])
    elif isinstance(result, Step):
        step = result
    elif isinstance(result, Status | str):
        step = Step(Status(result))
    else:
        raise ControllerException(
            f"{method} returned {type(result).__name__}; expected a Step, a Status or "
            "(Status, TwistStamped)"
        )
    status = Status(step.status)
    failure = Failure(step.failure)
    if status is Status.FAILED and failure is Failure.NONE:
        failure = Failure.UNKNOWN
    body: dict[str, Any] = {"status": status.value, "failure": failure.value}
    if step.cmd_vel is not None:
        values = checked_twist_stamped(step.cmd_vel, method)
        header = step.cmd_vel.header
        body["cmd_vel"] = {
            "frame_id": header.frame_id or frame_id,
            "stamp_ns": stamp_to_ns(header.stamp),
            "twist": values,
        }
    if step.feedback:
        body["feedback"] = {
            str(k): v.item() if isinstance(v, np.generic) else v for k, v in step.feedback.items()
        }
    return body
