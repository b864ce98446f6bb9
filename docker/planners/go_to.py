"""README's example controller, served from the mounted planner directory by compose.yaml."""

from __future__ import annotations

import math
from typing import Any

from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, GoalChecker, NoValidControl


class GoTo(Controller):
    """Turn towards the plan's far end and drive there."""

    def configure(self) -> None:
        self.speed = self.params.declare("speed", 0.3, "forward speed [m/s]")

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalChecker | None
    ) -> Any:
        if self.plan is None or len(self.plan) == 0:
            raise NoValidControl("no plan yet")
        gx, gy, _ = self.plan.xy_yaw[-1]  # plan: (N, 3) NumPy, the costmap's frame
        p = pose.pose.position  # pose: geometry_msgs/PoseStamped
        q = pose.pose.orientation
        yaw = 2.0 * math.atan2(q.z, q.w)
        error = math.atan2(gy - p.y, gx - p.x) - yaw
        cmd = TwistStamped(header=pose.header)
        cmd.twist.linear.x = self.speed
        cmd.twist.angular.z = math.atan2(math.sin(error), math.cos(error))
        return cmd
