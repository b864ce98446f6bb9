"""Check what a planner returned before it goes back to Nav2: right type, finite numbers."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from geometry_msgs.msg import Twist, TwistStamped

from nav2_pyif.exceptions import (
    ControllerException,
    Nav2Error,
    NoValidControl,
    NoValidPathCouldBeFound,
    PlannerException,
)
from nav2_pyif.messages import twist_to_list
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


def checked_plan(result: Any, frame_id: str, stamp_ns: int, method: str) -> Plan:
    """A Plan from what create_plan returned (Plan, nav_msgs/Path or array); finite values."""
    if isinstance(result, Plan):
        plan = result
    elif isinstance(result, np.ndarray):
        if result.ndim != 2 or result.shape[1] not in (2, 3, 7):
            raise PlannerException(
                f"{method} returned an array of shape {result.shape}; expected (N, 2) x, y, "
                f"(N, 3) x, y, yaw or (N, 7) x, y, z, qx, qy, qz, qw"
            )
        plan = Plan(result, frame_id, stamp_ns)
    elif hasattr(result, "poses") and hasattr(result, "header"):
        plan = Plan.from_msg(result)
    else:
        raise PlannerException(
            f"{method} returned {type(result).__name__}; expected nav_msgs.msg.Path, "
            f"nav2_pyif.Plan or a NumPy array"
        )
    finite = np.isfinite(plan.array)
    if not finite.all():
        rows = int((~finite.all(axis=1)).sum())
        raise NoValidPathCouldBeFound(
            f"{method} returned a path with non-finite values in {rows} of {len(plan)} poses"
        )
    return plan


def checked_bool(result: Any, method: str, error: type[Nav2Error]) -> bool:
    if not isinstance(result, (bool, np.bool_)):
        raise error(f"{method} returned {type(result).__name__}; expected bool")
    return bool(result)
