"""An artificial potential field controller in the function-delegate style:
plain module functions named in the plugin YAML (``python_module`` / ``python_delegates``).

    planner-host --key nav2_pyif/robot1/FollowPath --module nav2_pyif_planners.apf

(its functions are named after the roles, so no ``--delegate`` map is needed).

The robot is pulled towards a point ``lookahead`` metres down the plan and pushed away from
every costmap cell within ``influence_radius`` whose cost is at least ``obstacle_cost``.
Costs are read as unsigned bytes (0..255): 253/254 are the strongest obstacles, not negative
numbers as a signed int8 view of an OccupancyGrid would make them.
State lives in the module (as function delegates keep it), so one host process serves one APF robot.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Costmap, NoValidControl, Parameters, Plan
from nav2_pyif.geometry import (
    closest_index,
    limit_speed,
    point_at_distance,
    pose_xy_yaw,
    wrap,
)

DEFAULTS: dict[str, float] = {
    "max_linear_vel": 0.45,  # [m/s]
    "max_angular_vel": 1.8,  # [rad/s]
    "lookahead": 0.7,  # [m] attractive point down the plan
    "k_attractive": 1.0,
    "k_repulsive": 0.06,
    "influence_radius": 0.6,  # [m] obstacles farther away do not push
    "obstacle_cost": 200.0,  # cells with at least this (unsigned) cost push
    "k_heading": 2.5,  # angular gain on the heading error
    "xy_goal_tolerance": 0.2,  # [m] then turn to the goal heading
}

STATE: dict[str, Any] = {"params": dict(DEFAULTS), "plan": None, "index": 0, "limit": None}


def configure(params: Parameters) -> None:
    STATE["params"] = {name: float(params.declare(name, value)) for name, value in DEFAULTS.items()}
    STATE.update(plan=None, index=0, limit=None)


def set_plan(global_plan: Plan) -> None:
    STATE["plan"] = np.array(global_plan.xy_yaw)  # (N, 3): x, y, yaw
    STATE["index"] = 0


def set_speed_limit(speed_limit: float, is_percentage: bool) -> None:
    unlimited = speed_limit <= 0.0 or (is_percentage and speed_limit >= 100.0)
    STATE["limit"] = None if unlimited else (speed_limit, is_percentage)


def repulsion(
    costmap: Costmap, x: float, y: float, radius: float, threshold: float, gain: float
) -> np.ndarray:
    """Sum of repulsive forces (2,) from costly cells within ``radius`` of (x, y)."""
    r = math.ceil(radius / costmap.resolution)
    centre = costmap.world_to_map(x, y)
    if centre is None:
        return np.zeros(2)
    mx, my = centre
    x0, x1 = max(mx - r, 0), min(mx + r + 1, costmap.size_x)
    y0, y1 = max(my - r, 0), min(my + r + 1, costmap.size_y)
    window = costmap.data[y0:y1, x0:x1]  # uint8: read as unsigned
    cy, cx = np.nonzero((window >= threshold) & (window != Costmap.NO_INFORMATION))
    if len(cx) == 0:
        return np.zeros(2)
    cells = np.column_stack([cx + x0, cy + y0])
    obstacles = costmap.map_to_world_array(cells)
    away = np.array([x, y]) - obstacles
    d = np.maximum(np.hypot(away[:, 0], away[:, 1]), 0.5 * costmap.resolution)
    near = d < radius
    strength = gain * (1.0 / d[near] - 1.0 / radius) / d[near] ** 2
    force: np.ndarray = (away[near] / d[near, None] * strength[:, None]).sum(axis=0)
    return force / max(len(cx), 1) * 10.0  # normalised by the cell count, scaled to metres


def compute_velocity_commands(costmap: Costmap, pose: Any, twist: Any) -> Any:
    params, plan = STATE["params"], STATE["plan"]
    if plan is None or len(plan) == 0:
        raise NoValidControl("APF has no plan")
    x, y, yaw = pose_xy_yaw(pose)
    STATE["index"] = closest_index(plan[:, :2], x, y, STATE["index"], window=200)
    cmd = TwistStamped(header=pose.header)
    cmd.header.frame_id = "base_link"
    max_w = params["max_angular_vel"]
    goal = plan[-1]
    if math.hypot(goal[0] - x, goal[1] - y) < params["xy_goal_tolerance"]:
        cmd.twist.angular.z = float(np.clip(2.0 * wrap(goal[2] - yaw), -max_w, max_w))
        return cmd
    target = point_at_distance(plan[:, :2], STATE["index"], params["lookahead"])
    attraction = params["k_attractive"] * (target - np.array([x, y]))
    push = repulsion(
        costmap, x, y, params["influence_radius"], params["obstacle_cost"], params["k_repulsive"]
    )
    # Classic APF stalls where a wall ahead balances the pull (a doorway, a corridor mouth):
    # drop the part of the push that opposes travel along the plan, keep the sideways part.
    tangent = attraction / max(float(np.hypot(*attraction)), 1e-9)
    backwards = float(push @ tangent)
    if backwards < 0.0:
        push = push - backwards * tangent
    force = attraction + push
    heading_error = float(wrap(math.atan2(force[1], force[0]) - yaw))
    v_max = limit_speed(params["max_linear_vel"], STATE["limit"])
    distance_to_goal = math.hypot(goal[0] - x, goal[1] - y)
    v = v_max * max(0.0, math.cos(heading_error)) ** 2 * min(1.0, distance_to_goal / 0.5 + 0.2)
    cmd.twist.linear.x = float(v)
    cmd.twist.angular.z = float(np.clip(params["k_heading"] * heading_error, -max_w, max_w))
    return cmd
