"""What the reference path-following controllers share: progress along the plan, live
parameter updates, and turning to the goal's heading once within the goal tolerance."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, GoalTolerances, NoValidControl, Plan
from nav2_pyif.geometry import closest_index, pose_xy_yaw, wrap


class PathFollower(Controller):
    index = 0  # closest plan pose so far: progress never jumps back along the plan
    xy_goal_tolerance = 0.25  # [m] when Nav2 gives no goal checker
    goal_turn_rate = 1.5  # [rad/s] the most it turns in place at the goal

    def on_parameters_changed(self, changed: dict[str, Any]) -> None:
        self.configure()

    def set_plan(self, plan: Plan) -> None:
        super().set_plan(plan)
        self.index = 0

    def reset(self) -> None:
        self.index = 0

    def track(self, pose: Any) -> tuple[float, float, float, np.ndarray]:
        """(x, y, yaw, plan as (N, 3)) with ``index`` advanced to the closest plan pose."""
        if self.plan is None or len(self.plan) == 0:
            raise NoValidControl("no plan to follow")
        x, y, yaw = pose_xy_yaw(pose)
        path = self.plan.xy_yaw
        self.index = closest_index(path[:, :2], x, y, self.index, window=200)
        return x, y, yaw, path

    def command(self, pose: Any) -> Any:
        cmd = TwistStamped(header=pose.header)
        cmd.header.frame_id = self.robot_base_frame
        return cmd

    def turn_at_goal(
        self,
        cmd: Any,
        x: float,
        y: float,
        yaw: float,
        path: np.ndarray,
        goal_checker: GoalTolerances | None,
    ) -> bool:
        """Within the goal tolerance: fill ``cmd`` with a turn to the goal's heading."""
        tolerance = goal_checker.xy_goal_tolerance if goal_checker else self.xy_goal_tolerance
        goal = path[-1]
        if math.hypot(goal[0] - x, goal[1] - y) >= tolerance:
            return False
        error = float(wrap(goal[2] - yaw))
        cmd.twist.angular.z = float(np.clip(2.0 * error, -self.goal_turn_rate, self.goal_turn_rate))
        return True
