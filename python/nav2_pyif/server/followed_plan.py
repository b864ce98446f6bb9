"""The plan a controller follows and its goal: from ``set_plan`` on every distribution, and
from the control cycle on Lyrical, where controller_server transforms the plan itself and the
plugin sends it along with a cycle when it changed (PROTOCOL.md section 14)."""

from __future__ import annotations

from typing import Any

import numpy as np

from nav2_pyif._messages import pose_from_wire
from nav2_pyif.exceptions import InvalidPath
from nav2_pyif.plan import Plan


def follow_plan(
    controller: Any, path: dict[str, Any], goal: dict[str, Any] | None, *, in_cycle: bool = False
) -> None:
    """Hand the controller the plan (wire form) and set its ``global_goal`` first: Nav2's
    (``goal``, Lyrical) or else the plan's last pose, so the attribute means the same on every
    distribution. ``in_cycle``: the plan a Lyrical cycle carried, whose goal travels only when
    it changed (the plan pruned, the goal kept)."""
    plan = Plan.from_wire(path)
    if not np.isfinite(plan.array).all():
        raise InvalidPath("the plan sent to set_plan has non-finite values")
    if goal is not None:
        controller.global_goal = pose_from_wire(goal)
    elif in_cycle and controller.global_goal is not None:
        pass
    elif len(plan):
        last = plan.array[-1].tolist()
        wire = {"frame_id": plan.frame_id, "stamp_ns": plan.stamp_ns, "pose": last}
        controller.global_goal = pose_from_wire(wire)
    controller.set_plan(plan)
