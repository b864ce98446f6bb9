"""Nav2 MPPI's path handler (path_handler.cpp, Jazzy) in NumPy, run on the host before the
compiled step: drop the plan behind the robot's closest pose (searched within
max_robot_pose_search_dist of the plan's start), keep what follows up to prune_distance of
integrated length and inside the costmap, and pad it to the step's fixed number of points."""

from __future__ import annotations

import numpy as np
from nav2_pyif import Costmap, InvalidPath


class PathHandler:
    """The part of the global plan still ahead, pruned each cycle as Nav2 does. The plan's
    integrated length is summed once per plan, so a cycle looks at the poses it keeps (and
    those within the search distance), not at the whole plan."""

    def __init__(self, prune_distance: float, search_distance: float) -> None:
        self.prune_distance = prune_distance
        self.search_distance = search_distance
        self.set_plan(np.zeros((0, 3)))

    def set_plan(self, xy_yaw: np.ndarray) -> None:
        self.plan = np.asarray(xy_yaw, np.float64)
        steps = np.hypot(*np.diff(self.plan[:, :2], axis=0).T) if len(self.plan) > 1 else []
        self.along = np.concatenate([[0.0], np.cumsum(steps)])[: len(self.plan)]
        self.start = 0  # the plan behind this index is dropped

    @property
    def remaining(self) -> np.ndarray:
        return self.plan[self.start :]

    def first_after(self, index: int, distance: float) -> int:
        """Index of the first pose whose integrated distance from pose ``index`` exceeds
        ``distance`` (Nav2's first_after_integrated_distance); len(plan) when none does."""
        return int(np.searchsorted(self.along, self.along[index] + distance, side="right"))

    def transform(self, x: float, y: float, costmap: Costmap) -> np.ndarray:
        """(M, 3) the plan from the pose closest to (x, y) on, pruned; the plan behind that
        pose is dropped for good. Raises InvalidPath when nothing is left."""
        start, plan = self.start, self.plan
        if len(plan) == start:
            raise InvalidPath("Received plan with zero length")
        bound = max(self.first_after(start, self.search_distance), start + 1)
        near = plan[start:bound]
        closest = start + int(np.argmin(np.hypot(near[:, 0] - x, near[:, 1] - y)))
        ahead = plan[closest : self.first_after(closest, self.prune_distance)]
        inside = costmap.inside_world_array(ahead[:, :2])
        if not inside.all():
            ahead = ahead[: int(np.argmin(inside))]  # up to the first point off the costmap
        self.start = closest
        if len(ahead) == 0:
            raise InvalidPath("Resulting plan has 0 poses in it.")
        return ahead


def padded(path: np.ndarray, points: int) -> tuple[np.ndarray, int]:
    """(points, 3) float32: ``path`` then its last pose repeated, and its real length; a
    longer path is subsampled evenly, its ends kept (the step's shape is fixed)."""
    if len(path) > points:
        path = path[np.linspace(0, len(path) - 1, points).round().astype(int)]
    out = np.empty((points, 3), np.float32)
    out[: len(path)] = path
    out[len(path) :] = path[-1]
    return out, len(path)
