"""The large-message launch test's global planner: the reference A*, its path resampled to
exactly `poses` poses (10 000 by default: about 0.5 MB each way, as the plan reply and as
the controller's setPlan), after checking that the whole map arrived (`expected_cells`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from nav2_pyif import PlannerException
from nav2_pyif_planners.astar import AStar


class DensePlanner(AStar):
    def configure(self) -> None:
        super().configure()
        self.poses = self.params.declare("poses", 10_000, "poses in every plan")
        self.expected_cells = self.params.declare(
            "expected_cells", 0, "the costmap's size x and y it must have (0: any)"
        )

    def create_plan(self, start: Any, goal: Any, cancel_checker: Callable[[], bool]) -> Any:
        shape = self.costmap.data.shape
        if self.expected_cells and shape != (self.expected_cells, self.expected_cells):
            raise PlannerException(f"costmap is {shape}, expected {self.expected_cells} square")
        coarse = np.asarray(super().create_plan(start, goal, cancel_checker))
        along = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(coarse[:, :2], axis=0).T))))
        at = np.linspace(0.0, along[-1], int(self.poses))
        dense = np.column_stack([np.interp(at, along, coarse[:, i]) for i in range(2)])
        yaw = np.interp(at, along, np.unwrap(coarse[:, 2]))
        return np.column_stack([dense, yaw])
