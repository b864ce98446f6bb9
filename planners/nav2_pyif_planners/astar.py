"""A cost-aware A* global planner on Nav2's costmap (8-connected, like NavFn/Smac 2D).

Moving into a cell costs ``step * (1 + cost_weight * cost / 252)``: the plan keeps away from
inflated obstacles when it can. Cells at or above ``lethal_cost`` (default INSCRIBED, 253)
are impassable, unknown cells too unless ``allow_unknown``. The raw cell path is smoothed
and resampled to the costmap resolution; each pose faces the next, the last the goal's yaw.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable
from typing import Any

import numpy as np
from nav2_pyif import (
    Costmap,
    GlobalPlanner,
    GoalOccupied,
    GoalOutsideMapBounds,
    NoValidPathCouldBeFound,
    PlannerCancelled,
    StartOccupied,
    StartOutsideMapBounds,
)
from nav2_pyif.geometry import pose_xy_yaw

SQRT2 = math.sqrt(2.0)
MOVES = [
    (1, 0, 1.0),
    (-1, 0, 1.0),
    (0, 1, 1.0),
    (0, -1, 1.0),
    (1, 1, SQRT2),
    (1, -1, SQRT2),
    (-1, 1, SQRT2),
    (-1, -1, SQRT2),
]
CANCEL_CHECK_EVERY = 4096


class AStar(GlobalPlanner):
    def configure(self) -> None:
        self.cost_weight = self.params.declare(
            "cost_weight", 3.0, "how strongly the plan avoids inflated cells (0: shortest)"
        )
        self.lethal_cost = self.params.declare(
            "lethal_cost", 253, "cells with this cost or more are impassable"
        )
        self.allow_unknown = self.params.declare("allow_unknown", False)
        self.smoothing = self.params.declare("smoothing_window", 5, "moving-average cells")

    def on_parameters_changed(self, changed: dict[str, Any]) -> None:
        self.configure()

    def create_plan(self, start: Any, goal: Any, cancel_checker: Callable[[], bool]) -> Any:
        cm = self.costmap
        sx, sy, _ = pose_xy_yaw(start)
        gx, gy, gyaw = pose_xy_yaw(goal)
        s_cell = cm.world_to_map(sx, sy)
        g_cell = cm.world_to_map(gx, gy)
        if s_cell is None:
            raise StartOutsideMapBounds(f"start ({sx:.2f}, {sy:.2f}) is outside the costmap")
        if g_cell is None:
            raise GoalOutsideMapBounds(f"goal ({gx:.2f}, {gy:.2f}) is outside the costmap")
        if not self._passable(cm.cost(*s_cell)):
            raise StartOccupied(f"start ({sx:.2f}, {sy:.2f}) has cost {cm.cost(*s_cell)}")
        if not self._passable(cm.cost(*g_cell)):
            raise GoalOccupied(f"goal ({gx:.2f}, {gy:.2f}) has cost {cm.cost(*g_cell)}")
        cells = self._search(cm, s_cell, g_cell, cancel_checker)
        xy = cm.map_to_world_array(np.array(cells, dtype=np.float64))
        xy[0], xy[-1] = (sx, sy), (gx, gy)
        xy = self._smooth(xy)
        poses = np.zeros((len(xy), 3))
        poses[:, :2] = xy
        if len(xy) > 1:
            d = np.diff(xy, axis=0)
            poses[:-1, 2] = np.arctan2(d[:, 1], d[:, 0])
        poses[-1, 2] = gyaw
        return poses

    def _passable(self, cost: int) -> bool:
        if cost == Costmap.NO_INFORMATION:
            return bool(self.allow_unknown)
        return cost < self.lethal_cost

    def _search(
        self,
        cm: Costmap,
        start: tuple[int, int],
        goal: tuple[int, int],
        cancel_checker: Callable[[], bool],
    ) -> list[tuple[int, int]]:
        width, height = cm.size_x, cm.size_y
        costs = cm.data.ravel().tolist()
        blocked = [not self._passable(c) for c in costs]
        factor = [1.0 + self.cost_weight * min(c, 252) / 252.0 for c in costs]
        start_i, goal_i = start[1] * width + start[0], goal[1] * width + goal[0]
        gx, gy = goal
        g_score = {start_i: 0.0}
        parent = {start_i: -1}
        heap = [(math.hypot(start[0] - gx, start[1] - gy), 0.0, start_i)]
        closed: set[int] = set()
        expanded = 0
        if cancel_checker():
            raise PlannerCancelled("cancelled before the search started")
        while heap:
            _, g, i = heapq.heappop(heap)
            if i in closed:
                continue
            if i == goal_i:
                break
            closed.add(i)
            expanded += 1
            if expanded % CANCEL_CHECK_EVERY == 0 and cancel_checker():
                raise PlannerCancelled(f"cancelled after expanding {expanded} cells")
            x, y = i % width, i // width
            for dx, dy, step in MOVES:
                nx, ny = x + dx, y + dy
                if nx < 0 or ny < 0 or nx >= width or ny >= height:
                    continue
                j = ny * width + nx
                if blocked[j] or j in closed:
                    continue
                if dx and dy and (blocked[y * width + nx] or blocked[ny * width + x]):
                    continue  # no diagonal squeeze between two blocked cells
                ng = g + step * factor[j]
                if ng < g_score.get(j, math.inf):
                    g_score[j] = ng
                    parent[j] = i
                    heapq.heappush(heap, (ng + math.hypot(nx - gx, ny - gy), ng, j))
        if goal_i not in parent:
            raise NoValidPathCouldBeFound(
                f"no path from cell {start} to cell {goal} (expanded {expanded} cells)"
            )
        path = []
        i = goal_i
        while i != -1:
            path.append((i % width, i // width))
            i = parent[i]
        return path[::-1]

    def _smooth(self, xy: np.ndarray) -> np.ndarray:
        window = int(self.smoothing)
        if window < 2 or len(xy) <= window:
            return xy
        kernel = np.ones(window) / window
        padded = np.pad(xy, ((window // 2, window - 1 - window // 2), (0, 0)), mode="edge")
        smooth = np.column_stack(
            [np.convolve(padded[:, k], kernel, mode="valid") for k in range(2)]
        )
        smooth[0], smooth[-1] = xy[0], xy[-1]
        return smooth
