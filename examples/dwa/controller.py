"""A Dynamic Window Approach controller (Fox, Burgard and Thrun, 1997) in NumPy, on
nav2_pyif's helpers: ``self.control_period`` for the window, ``costmap.obstacle_points()`` for
the clearance, ``costmap.footprint_costs`` for collisions, ``carrot`` for where to head, the goal
checker's tolerances for the final turn.

Each cycle samples the (v, w) reachable within one control period at the given accelerations,
rolls each pair out as an arc over ``horizon`` seconds and keeps the cheapest admissible one (the
robot can brake before its footprint, grown by ``margin``, would touch a lethal cell): near the
plan, close to the carrot at the end and facing it, fast, and clear of obstacles.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, Costmap, NoValidControl, carrot, pose_xy_yaw, wrap

from dwa.rollout import STEP, arcs, nearest_distance

SAMPLES = (5, 11)  # v, w values in the window


class DWA(Controller):
    def configure(self) -> None:
        declare = self.params.declare
        self.max_speed = declare("max_speed", 0.5, "[m/s]")
        self.max_turn = declare("max_turn", 1.5, "[rad/s]")
        self.accel = declare("accel", 1.0, "[m/s^2]")
        self.turn_accel = declare("turn_accel", 4.0, "[rad/s^2]")
        self.horizon = declare("horizon", 1.2, "[s] of rolled-out motion")
        self.lookahead = declare("lookahead", 1.0, "[m] carrot distance along the plan")
        self.clear = declare("clearance", 0.4, "[m] from obstacles below which paths cost more")
        self.margin = declare("margin", 0.03, "[m] kept between the footprint and obstacles")
        self.progress = 0  # the plan index reached: never goes backwards
        self.outline: Any = None  # (M, 2) the grown footprint's outline, with the first costmap

    def set_plan(self, plan: Any) -> None:
        super().set_plan(plan)
        self.progress = 0

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        if self.plan is None or len(self.plan) == 0:
            raise NoValidControl("no plan yet")
        x, y, yaw = pose_xy_yaw(pose)
        gx, gy, gyaw = self.plan.xy_yaw[-1]
        cmd = TwistStamped(header=pose.header)
        tolerance = goal_checker.xy_goal_tolerance if goal_checker else 0.25
        if np.hypot(gx - x, gy - y) < 0.5 * tolerance:  # there: turn to the goal's heading
            cmd.twist.angular.z = float(np.clip(2.0 * wrap(gyaw - yaw), -1.0, 1.0))
            return cmd
        (cx, cy), self.progress = carrot(self.plan.xy_yaw, x, y, self.lookahead, self.progress)
        v, w = self.window(velocity.linear.x, velocity.angular.z)
        poses = arcs(x, y, yaw, v, w, self.horizon)  # (K, T, 3)
        ahead = self.plan.xy[self.progress : self.progress + 80]  # (P, 2) the plan ahead
        cost = self.cost(poses, v, (cx, cy), ahead) + self.inadmissible(poses, v)
        if not np.isfinite(cost).any():
            raise NoValidControl("every trajectory of the dynamic window collides")
        k = int(np.argmin(cost))
        cmd.twist.linear.x, cmd.twist.angular.z = float(v[k]), float(w[k])
        return cmd

    def window(self, v0: float, w0: float) -> tuple[Any, Any]:
        """(K,) v [m/s] and (K,) w [rad/s]: the grid reachable within one control period."""
        dt = self.control_period or 0.05  # [s] the controller server's period
        v = np.linspace(
            max(0.0, v0 - self.accel * dt), min(self.max_speed, v0 + self.accel * dt), SAMPLES[0]
        )
        dw = self.turn_accel * dt
        w = np.linspace(max(-self.max_turn, w0 - dw), min(self.max_turn, w0 + dw), SAMPLES[1])
        vv, ww = np.meshgrid(v, w)
        return vv.ravel(), ww.ravel()

    def cost(self, poses: Any, v: Any, target: tuple[float, float], ahead: Any) -> Any:
        """(K,) the cost of each of the (K, T, 3) trajectories at (K,) speeds v [m/s], heading
        for ``target`` (x, y) [m] along ``ahead``, (P, 2) points of the plan."""
        cx, cy = target
        end, sampled = poses[:, -1], poses[:, 3::4, :2]  # every 0.2 s for the distances
        obstacles = self.costmap.obstacle_points()  # (M, 2): the lethal cells' edges
        facing = wrap(np.arctan2(cy - end[:, 1], cx - end[:, 0]) - end[:, 2])
        return (
            np.hypot(cx - end[:, 0], cy - end[:, 1])
            + 2.0 * nearest_distance(sampled, ahead).mean(axis=1)  # keep off the corners
            + 0.3 * np.abs(facing)
            + 0.2 * (self.max_speed - v)
            + 2.0 * np.maximum(0.0, self.clear - nearest_distance(sampled, obstacles).min(axis=1))
        )

    def inadmissible(self, poses: Any, v: Any) -> Any:
        """(K,) inf where the robot could not brake before its grown footprint touched a
        lethal cell at v (cells beyond the rolling window count free), else 0."""
        if self.outline is None:  # half-cell spacing: no cell slips between two points
            grow = 1.0 + self.margin / self.costmap.inscribed_radius
            self.outline = grow * self.costmap.footprint_outline(self.costmap.resolution / 2)
        hits = self.costmap.footprint_costs(poses, self.outline, unknown_as=0) >= Costmap.LETHAL
        impact = np.where(hits.any(axis=1), hits.argmax(axis=1) * STEP, np.inf)  # [s]
        braking = v / (2 * self.accel) + 2 * (self.control_period or 0.05)  # [s]
        return np.where(impact <= braking, np.inf, 0.0)
