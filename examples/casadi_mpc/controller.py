"""A model predictive controller solved by CasADi/IPOPT (the extra ``casadi``).

Its time step is the controller server's period (``self.control_period``): the first control
of each solution is the one applied for exactly that long. The reference is the plan from the
robot on, a pose every ``max_speed * dt`` metres; the plan's last pose, the goal, holds its
heading, so the MPC turns on the spot at the end as the goal check wants.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, NoValidControl, closest_index, pose_xy_yaw

from casadi_mpc.problem import OBSTACLES, Limits, Problem


class MPC(Controller):
    def configure(self) -> None:
        self.steps = self.params.declare("steps", 20, "horizon: steps of one control period")
        self.limits = Limits(
            self.params.declare("max_speed", 0.4, "[m/s]"),
            self.params.declare("max_turn", 1.2, "[rad/s]"),
            self.params.declare("safe_distance", 0.3, "[m] kept from obstacle cells, softly"),
        )
        self.dt = self.control_period or 0.05  # [s] None only from a plugin of before the field
        self.problem = Problem(self.steps, self.dt, self.limits)
        self.progress = 0

    def set_plan(self, plan: Any) -> None:
        super().set_plan(plan)
        self.progress = 0
        xy = plan.xy
        self.arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])  # [m]

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        if self.plan is None or len(self.plan) == 0:
            raise NoValidControl("no plan yet")
        x, y, yaw = pose_xy_yaw(pose)
        self.progress = closest_index(self.plan.xy, x, y, self.progress, window=200)
        ahead = self.arc[self.progress] + self.limits.max_speed * self.dt * np.arange(
            1, self.steps + 1
        )
        ref = self.plan.xy_yaw[np.minimum(np.searchsorted(self.arc, ahead), len(self.arc) - 1)]
        ref[:, 2] = np.unwrap(np.concatenate([[yaw], ref[:, 2]]))[1:]  # no 2 pi jumps for IPOPT
        obstacles = self.costmap.obstacle_points()  # (M, 2) the lethal cells' edges
        nearest = np.argsort(np.hypot(obstacles[:, 0] - x, obstacles[:, 1] - y))[:OBSTACLES]
        padded = np.full((OBSTACLES, 2), 1e3)  # "far away" where there are fewer
        padded[: len(nearest)] = obstacles[nearest]
        v, w = self.problem.solve(np.array([x, y, yaw]), ref.T, padded.T)
        cmd = TwistStamped(header=pose.header)
        cmd.twist.linear.x, cmd.twist.angular.z = v, w
        return cmd
