"""Nav2 Lyrical's FeasiblePathHandler pruning rule as a nav2_pyif path handler (parameter
names and defaults from nav2_controller/plugins/feasible_path_handler.cpp), served to
controller_server::

    planner-host --key nav2_pyif/robot1/path_handler \\
        --planner nav2_pyif_planners.path_handler:PruningPathHandler

Each cycle: the plan's pose closest to the robot, searched from where the robot got to over
``max_robot_pose_search_dist`` of plan, starts the segment (never fewer than two poses left
before the search's end), which runs ``prune_distance`` of plan further. The poses before it
are pruned: the next search starts there. The plugin crops the segment at the costmap's edge
as Nav2's does. Not here: Nav2's ``enforce_path_inversion`` and ``enforce_path_rotation``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from nav2_pyif import InvalidPath, PathHandler, Plan
from nav2_pyif.geometry import arc_lengths
from nav2_pyif.params import ParamValue


def first_after_distance(xy: np.ndarray, begin: int, distance: float) -> int:
    """nav2_util's first_after_integrated_distance: the first index after ``begin`` at which
    the plan's length from ``begin`` exceeds ``distance``; ``len(xy)`` when none does."""
    if begin >= len(xy):
        return len(xy)
    beyond = np.flatnonzero(arc_lengths(xy[begin:]) > distance)
    return begin + int(beyond[0]) if len(beyond) else len(xy)


class PruningPathHandler(PathHandler):
    """The segment of the plan ahead of the robot, with the part behind it pruned."""

    def configure(self) -> None:
        p = self.params
        # Nav2's default: half the costmap's larger side
        extent = max(self.costmap.size_x, self.costmap.size_y) * self.costmap.resolution / 2.0
        p.declare("max_robot_pose_search_dist", extent, "[m] plan searched for the closest pose")
        p.declare("prune_distance", 2.0, "[m] plan ahead of the closest pose")
        p.declare("reject_unit_path", False, "a plan of one pose is InvalidPath")
        self._start = 0  # where the robot got to: the poses before are pruned
        self.on_parameters_changed({})

    def on_parameters_changed(self, changed: dict[str, ParamValue]) -> None:
        search = float(self.params["max_robot_pose_search_dist"])
        self.search_distance = search if search >= 0.0 else float("inf")
        self.prune_distance = float(self.params["prune_distance"])
        self.reject_unit_path = bool(self.params["reject_unit_path"])

    def set_plan(self, plan: Plan) -> None:
        super().set_plan(plan)
        self._start = 0

    def find_plan_segment(self, pose: Any) -> tuple[int, int]:
        xy = self.plan.array[:, :2]
        if len(xy) == 0:
            raise InvalidPath("Received plan with zero length")
        if self.reject_unit_path and len(xy) == 1:
            raise InvalidPath("Received plan with length of one")
        begin = self._start
        bound = first_after_distance(xy, begin, self.search_distance)
        robot = np.array([pose.pose.position.x, pose.pose.position.y])
        closest = begin + int(np.argmin(np.hypot(*(xy[begin:bound] - robot).T)))
        # at least two poses, so that the end of the plan keeps a direction
        if bound - begin > 1 and closest == bound - 1:
            closest = bound - 2
        end = max(first_after_distance(xy, closest, self.prune_distance), closest + 1)
        self._start = closest
        return closest, end
