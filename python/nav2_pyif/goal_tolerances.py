"""The goal checker's tolerances, as Nav2's GoalChecker::getTolerances reports them: what a
controller receives with each control cycle's call."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class GoalTolerances:
    xy_goal_tolerance: float  # [m]
    yaw_goal_tolerance: float  # [rad]
    trans_stopped_velocity: float  # [m/s]
    rot_stopped_velocity: float  # [rad/s]
    #: [m] Nav2 Lyrical's path length tolerance (SimpleGoalChecker: the goal counts only once
    #: the remaining plan is shorter); None where the checker has none, and before Lyrical.
    path_length_tolerance: float | None = None

    @classmethod
    def from_wire(cls, wire: dict[str, Any]) -> GoalTolerances:
        return cls(**wire)

    def to_wire(self) -> dict[str, float]:
        wire = {
            "xy_goal_tolerance": self.xy_goal_tolerance,
            "yaw_goal_tolerance": self.yaw_goal_tolerance,
            "trans_stopped_velocity": self.trans_stopped_velocity,
            "rot_stopped_velocity": self.rot_stopped_velocity,
        }
        if self.path_length_tolerance is not None:
            wire["path_length_tolerance"] = self.path_length_tolerance
        return wire

    def is_goal_reached(
        self, x: float, y: float, yaw: float, goal_x: float, goal_y: float, goal_yaw: float
    ) -> bool:
        """Nav2's SimpleGoalChecker rule: within xy and yaw tolerance of the goal."""
        if math.hypot(goal_x - x, goal_y - y) > self.xy_goal_tolerance:
            return False
        dyaw = math.atan2(math.sin(goal_yaw - yaw), math.cos(goal_yaw - yaw))
        return abs(dyaw) <= self.yaw_goal_tolerance
