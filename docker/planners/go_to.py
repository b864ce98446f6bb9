"""README's example controller, served from the mounted planner directory by compose.yaml."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, GoalTolerances, NoValidControl


class GoTo(Controller):
    """Steer towards a carrot: the first plan point `lookahead` metres from the robot."""

    def configure(self) -> None:
        self.speed = self.params.declare("speed", 0.3, "forward speed [m/s]")
        self.lookahead = self.params.declare("lookahead", 0.4, "carrot distance [m]")

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        if self.plan is None or len(self.plan) == 0:
            raise NoValidControl("no plan yet")
        p = pose.pose.position  # pose: geometry_msgs/PoseStamped
        q = pose.pose.orientation
        yaw = 2.0 * math.atan2(q.z, q.w)
        xy = self.plan.xy_yaw[:, :2]  # plan: (N, 3) NumPy, the costmap's frame
        distance = np.hypot(xy[:, 0] - p.x, xy[:, 1] - p.y)
        nearest = int(np.argmin(distance))
        beyond = np.flatnonzero(distance[nearest:] >= self.lookahead)
        cx, cy = xy[nearest + beyond[0]] if len(beyond) else xy[-1]
        error = math.atan2(cy - p.y, cx - p.x) - yaw
        error = math.atan2(math.sin(error), math.cos(error))  # to [-pi, pi]
        cmd = TwistStamped(header=pose.header)
        cmd.twist.linear.x = self.speed * max(0.0, math.cos(error))  # turn first, then drive
        cmd.twist.angular.z = 2.0 * error
        return cmd
