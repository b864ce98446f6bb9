"""Planners that say in the host's log what Lyrical's Nav2 gave them (test_lyrical_api.py): the
plan and global goal a controller follows, a planner's viapoints, the goal checks Nav2's own
controllers make with isGoalXYReached. Each report is a WARNING line starting with
"report:", so it shows at any host log level."""

from __future__ import annotations

import dataclasses
import itertools
from typing import Any

import numpy as np
from nav2_pyif import GoalTolerances, Plan
from nav2_pyif_planners.astar import AStar
from nav2_pyif_planners.checker_plugins import StoppedGoalChecker
from nav2_pyif_planners.pure_pursuit import RegulatedPurePursuit


class ReportingPursuit(RegulatedPurePursuit):
    """The reference pure pursuit; reports each plan it is given (its poses, whether they are
    the previous plan's again, the global goal) and the goal checker's path length tolerance
    it sees."""

    def configure(self) -> None:
        super().configure()
        self._last: np.ndarray | None = None
        self._tolerance_reported = False

    def set_plan(self, plan: Plan) -> None:
        super().set_plan(plan)
        xy = np.array(plan.array[:, :2])
        same = self._last is not None and np.array_equal(self._last, xy)
        self._last = xy
        goal = self.global_goal.pose.position if self.global_goal is not None else None
        where = f"({goal.x:.3f}, {goal.y:.3f})" if goal is not None else "none"
        self.logger.warning(
            "report: plan of %d poses, same as the last: %s, global goal %s", len(plan), same, where
        )

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        if goal_checker is not None and not self._tolerance_reported:
            self._tolerance_reported = True
            self.logger.warning(
                "report: path_length_tolerance=%s", goal_checker.path_length_tolerance
            )
        return super().compute_velocity_commands(pose, velocity, goal_checker)


class ThroughViapoints(AStar):
    """A* from the start through each viapoint to the goal; reports the viapoints."""

    def create_plan(self, start: Any, goal: Any, cancel_checker: Any) -> Any:
        stops = [start, *self.viapoints, goal]
        self.logger.warning(
            "report: %d viapoints: %s",
            len(self.viapoints),
            [(round(p.pose.position.x, 3), round(p.pose.position.y, 3)) for p in self.viapoints],
        )
        legs = [super().create_plan(a, b, cancel_checker) for a, b in itertools.pairwise(stops)]
        return np.vstack([legs[0], *(leg[1:] for leg in legs[1:])])


class ReportingGoalChecker(StoppedGoalChecker):
    """Nav2's StoppedGoalChecker with a path length tolerance of 1.5 m; reports the first
    isGoalXYReached (xy only) check Nav2 makes."""

    def configure(self) -> None:
        super().configure()
        self._xy_reported = False

    def get_tolerances(self) -> GoalTolerances | None:
        return dataclasses.replace(super().get_tolerances(), path_length_tolerance=1.5)

    def is_goal_xy_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
        reached = super().is_goal_xy_reached(pose, goal, velocity)
        if not self._xy_reported:
            self._xy_reported = True
            self.logger.warning("report: is_goal_xy_reached asked: %s", reached)
        return reached
