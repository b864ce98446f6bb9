"""Regulated pure pursuit (Nav2's nav2_regulated_pure_pursuit_controller), in NumPy.

Follows a carrot down the plan, a lookahead scaled with speed
(``use_velocity_scaled_lookahead_dist``, Nav2's option; else ``lookahead_dist``), turning
with curvature 2 y / L^2 (carrot in the robot frame). The speed is regulated down on tight
curves, near obstacles (from the costmap's inflation ramp) and when approaching the goal;
the robot first rotates in place towards the path when it points far away from it, and to
the goal's heading once within the goal tolerance. A collision check projects the commanded
arc forward and refuses (NoValidControl) to drive into a lethal cell.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np
from nav2_pyif import Costmap, GoalTolerances, NoValidControl
from nav2_pyif.geometry import (
    limit_speed,
    point_at_distance,
    remaining_length,
)

from nav2_pyif_planners.follower import PathFollower


class RegulatedPurePursuit(PathFollower):
    """Debug output ``lookahead_point``: the carrot, as Nav2's controller publishes it."""

    debug_outputs: ClassVar[dict[str, str]] = {"lookahead_point": "geometry_msgs/msg/PointStamped"}

    def configure(self) -> None:
        p = self.params
        self.desired_linear_vel = p.declare("desired_linear_vel", 0.5, "[m/s]")
        self.lookahead_dist = p.declare("lookahead_dist", 0.6, "[m] when not velocity-scaled")
        self.scaled_lookahead = p.declare(
            "use_velocity_scaled_lookahead_dist",
            True,
            "lookahead = speed x lookahead_time (Nav2's default: false, lookahead_dist)",
        )
        self.lookahead_time = p.declare("lookahead_time", 1.5, "[s] velocity-scaled lookahead")
        self.min_lookahead = p.declare("min_lookahead_dist", 0.3, "[m]")
        self.max_lookahead = p.declare("max_lookahead_dist", 0.9, "[m]")
        self.rotate_vel = p.declare("rotate_to_heading_angular_vel", 1.8, "[rad/s]")
        self.rotate_min_angle = p.declare("rotate_to_heading_min_angle", 0.785, "[rad]")
        self.min_radius = p.declare("regulated_linear_scaling_min_radius", 0.9, "[m]")
        self.min_regulated_speed = p.declare("regulated_linear_scaling_min_speed", 0.25, "[m/s]")
        self.cost_scaling_dist = p.declare("cost_scaling_dist", 0.6, "[m]")
        self.cost_scaling_gain = p.declare("cost_scaling_gain", 1.0)
        self.inflation_scaling = p.declare(
            "inflation_cost_scaling_factor", 3.0, "must match the inflation layer"
        )
        self.inscribed_radius = p.declare(
            "inscribed_radius", -1.0, "[m] the footprint's; < 0: the costmap's, as Nav2's"
        )
        self.approach_dist = p.declare("approach_velocity_scaling_dist", 0.6, "[m]")
        self.min_approach_vel = p.declare("min_approach_linear_velocity", 0.05, "[m/s]")
        self.collision_time = p.declare("max_allowed_time_to_collision", 1.0, "[s]")
        self.xy_goal_tolerance = p.declare("xy_goal_tolerance", 0.25, "[m] when no goal checker")
        self.index = 0

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        x, y, yaw, path = self.track(pose)
        cmd = self.command(pose)
        self.goal_turn_rate = self.rotate_vel
        if self.turn_at_goal(cmd, x, y, yaw, path, goal_checker):
            return cmd

        lookahead = self.lookahead_dist
        if self.scaled_lookahead:
            speed = abs(velocity.linear.x)
            lookahead = float(
                np.clip(speed * self.lookahead_time, self.min_lookahead, self.max_lookahead)
            )
        carrot = point_at_distance(path[:, :2], self.index, lookahead)
        self.publish_debug("lookahead_point", carrot[:2])
        dx, dy = carrot[0] - x, carrot[1] - y
        cx = math.cos(yaw) * dx + math.sin(yaw) * dy  # carrot in the robot frame
        cy = -math.sin(yaw) * dx + math.cos(yaw) * dy
        angle_to_carrot = math.atan2(cy, cx)
        if abs(angle_to_carrot) > self.rotate_min_angle:
            cmd.twist.angular.z = math.copysign(self.rotate_vel, angle_to_carrot)
            return cmd

        distance_sq = cx * cx + cy * cy
        curvature = 2.0 * cy / distance_sq if distance_sq > 1e-6 else 0.0
        v = self._regulated_speed(curvature, x, y)
        cmd.twist.linear.x = v
        cmd.twist.angular.z = v * curvature
        self._check_collision(x, y, yaw, v, v * curvature)
        return cmd

    def _regulated_speed(self, curvature: float, x: float, y: float) -> float:
        v_max = limit_speed(self.desired_linear_vel, self.speed_limit)
        v = v_max
        if abs(curvature) > 1e-9 and 1.0 / abs(curvature) < self.min_radius:
            v *= (1.0 / abs(curvature)) / self.min_radius
        cost = self.costmap.cost_at_world(x, y)
        if 0 < cost < Costmap.INSCRIBED:
            # invert the inflation ramp: cost = 252 exp(-k (d - r)) -> distance to obstacle d
            inscribed = self.inscribed_radius
            if inscribed < 0.0:
                inscribed = self.costmap.inscribed_radius
            d = inscribed - math.log(cost / 252.0) / self.inflation_scaling
            if d < self.cost_scaling_dist:
                v *= self.cost_scaling_gain * d / self.cost_scaling_dist
        v = max(v, min(self.min_regulated_speed, v_max))
        assert self.plan is not None
        remaining = remaining_length(self.plan.xy, self.index)
        if remaining < self.approach_dist:
            v = max(v * remaining / self.approach_dist, self.min_approach_vel)
        return min(v, v_max)

    def _check_collision(self, x: float, y: float, yaw: float, v: float, w: float) -> None:
        steps = max(1, int(self.collision_time / 0.05))
        t = np.arange(1, steps + 1) * 0.05
        headings = yaw + w * t
        if abs(w) > 1e-6:
            xs = x + v / w * (np.sin(headings) - math.sin(yaw))
            ys = y - v / w * (np.cos(headings) - math.cos(yaw))
        else:
            xs, ys = x + v * t * math.cos(yaw), y + v * t * math.sin(yaw)
        costs = self.costmap.footprint_costs(np.column_stack([xs, ys, headings]))
        hits = np.nonzero(costs == Costmap.LETHAL)[0]
        if len(hits):
            raise NoValidControl(
                f"collision ahead in {t[hits[0]]:.2f} s at ({xs[hits[0]]:.2f}, {ys[hits[0]]:.2f})"
            )
