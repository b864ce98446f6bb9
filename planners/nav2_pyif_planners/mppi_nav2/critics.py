"""Nav2 MPPI's critics (nav2_mppi_controller/src/critics, Jazzy), in JAX: each scores every
rollout, (batch,) float32, from the same data, and may say that every rollout collides (Nav2's
``fail_flag``: the optimizer then resets and retries, and gives up with NoValidControl).

Nav2 loops over rollouts and their points and breaks at a collision; here the loops are
masks over (batch, steps) arrays with the same result. Where a result is not the same, the
docstring says so."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, NamedTuple

import jax.numpy as jnp

from nav2_pyif_planners.mppi_nav2.costs import (
    INSCRIBED,
    LETHAL,
    NO_INFORMATION,
    Grid,
    footprint_cost,
    point_cost,
)
from nav2_pyif_planners.mppi_nav2.models import Controls, running_sum
from nav2_pyif_planners.mppi_nav2.params import Critic, Settings

PI = math.pi


class CriticData(NamedTuple):
    """What critics score. Rollouts x, y, yaw: (T, batch) poses after each step, with the
    heading's ``cos`` and ``sin``; ``v``: the velocities they moved with, (T, batch) per
    axis, the robot's own speed first. ``pose``
    (x, y, yaw) the robot's; ``goal`` (x, y, yaw) the plan's last pose. ``path`` (P, 3) the
    pruned plan padded to P with its last pose, ``count`` its real length, ``valid`` (P,)
    whether each plan point is free (Nav2's path_pts_valid), ``furthest`` the index of the
    plan point furthest along reached by the rollouts. ``goal_tolerance``: the goal checker's
    xy tolerance, negative when Nav2 gave none."""

    x: Any
    y: Any
    yaw: Any
    cos: Any
    sin: Any
    v: Controls
    pose: Any
    goal: Any
    path: Any
    count: Any
    valid: Any
    furthest: Any
    grid: Grid
    goal_tolerance: Any


def normalize(angle: Any) -> Any:
    """Nav2's normalize_angles: into [-pi, pi) (Nav2's fmod form gives pi rather than -pi
    for some odd multiples of pi; the cost is the same). floor, not fmod: half the time on a
    CPU."""
    return angle - 2.0 * PI * jnp.floor((angle + PI) * (0.5 / PI))


def within(data: CriticData, threshold: Any) -> Any:
    """The robot is closer than ``threshold`` to the goal (withinPositionGoalTolerance)."""
    dx, dy = data.pose[0] - data.goal[0], data.pose[1] - data.goal[1]
    return dx * dx + dy * dy < threshold * threshold


def weighted(cost: Any, critic: Critic, weight: float | None = None) -> Any:
    """``cost * weight``, to the critic's cost_power when it is above 1."""
    out = cost * (critic["cost_weight"] if weight is None else weight)
    return out ** critic["cost_power"] if critic["cost_power"] > 1 else out


def constraint(data: CriticData, c: Critic, s: Settings) -> Any:
    """Speeds outside [vx_min, vx_max] (Omni: the signed total speed; Ackermann: also turns
    tighter than min_turning_r), integrated over time. Nav2 reads vy_max here even for
    DiffDrive (its default, 0.5, widens the band): so does this."""
    max_vel = math.hypot(s.vx_max, s.vy_max)
    min_vel = (1.0 if s.vx_min > 0.0 else -1.0) * math.hypot(s.vx_min, s.vy_max)
    v = data.v.vx
    if s.motion_model == "Omni":
        v = jnp.where(data.v.vx > 0.0, 1.0, -1.0) * jnp.hypot(data.v.vx, data.v.vy)
    out = jnp.maximum(v - max_vel, 0.0) + jnp.maximum(min_vel - v, 0.0)
    if s.motion_model == "Ackermann":
        out = out + jnp.maximum(s.min_turning_r - jnp.abs(data.v.vx) / jnp.abs(data.v.wz), 0.0)
    return weighted((out * s.model_dt).sum(axis=0), c)


def _collides(cost: Any, consider_footprint: bool, s: Settings) -> Any:
    """Nav2's inCollision on a cost: lethal; inscribed unless the footprint was checked;
    unknown unless the costmap tracks unknown space."""
    hit = cost == LETHAL
    if not consider_footprint:
        hit = hit | (cost == INSCRIBED)
    if not s.track_unknown_space:
        hit = hit | (cost == NO_INFORMATION)
    return hit


def _footprint_where_needed(data: CriticData, x: Any, y: Any, cos: Any, sin: Any, cost: Any) -> Any:
    """The footprint's cost where the centre's reaches the possible-collision cost (or when
    that is unknown), else the centre's."""
    possible = data.grid.robot[0]
    need = (cost >= possible) | (possible < 1.0)
    return jnp.where(need, footprint_cost(data.grid, x, y, cos, sin), cost)


def cost_critic(data: CriticData, c: Critic, s: Settings) -> tuple[Any, Any]:
    """CostCritic: every trajectory_point_step-th pose's centre cost, critical_cost from
    near_collision_cost up, collision_cost for a rollout that collides (the footprint
    checked where it may touch, with consider_footprint)."""
    step = c["trajectory_point_step"]
    count = s.time_steps // step
    x, y = data.x[::step][:count], data.y[::step][:count]
    cost = point_cost(data.grid, x, y)
    if c["consider_footprint"]:
        cos, sin = data.cos[::step][:count], data.sin[::step][:count]
        score = _footprint_where_needed(data, x, y, cos, sin, cost)
    else:
        score = cost
    hit = (cost >= 1.0) & _collides(score, c["consider_footprint"], s)
    near_goal = within(data, c["near_goal_distance"])
    added = jnp.where(
        cost >= c["near_collision_cost"],
        c["critical_cost"],
        jnp.where(near_goal, 0.0, cost),
    )
    collide = hit.any(axis=0)
    total = jnp.where(collide, c["collision_cost"], added.sum(axis=0))
    return weighted(total, c, c["cost_weight"] / 254.0 / count), collide.all()


def obstacles(data: CriticData, c: Critic, s: Settings) -> tuple[Any, Any]:
    """ObstaclesCritic: distance to obstacles from the inflation's costs, critical_weight
    for rollouts closer than collision_margin_distance or colliding, repulsion_weight for
    how close they come (normalised by the least)."""
    cost = point_cost(data.grid, data.x, data.y)
    inside = cost < NO_INFORMATION  # off-map poses are never checked by footprint
    footprint = c["consider_footprint"]
    if footprint:
        checked = _footprint_where_needed(data, data.x, data.y, data.cos, data.sin, cost)
        possible = data.grid.robot[0]
        used = inside & ((cost >= possible) | (possible < 1.0))
        cost = jnp.where(inside, checked, cost)
    else:
        used = jnp.zeros_like(inside)
    counts = cost >= 1.0
    hit = counts & _collides(cost, footprint, s)
    # poses before the first collision: Nav2 stops scoring a rollout there
    before = running_sum(hit.astype(jnp.int32)) == 0
    _, inscribed, radius, scale = (data.grid.robot[i] for i in range(4))
    active = counts & before & (radius != 0.0) & (scale != 0.0)
    safe_scale = jnp.where(scale == 0.0, 1.0, scale)
    dist = (scale * inscribed - jnp.log(jnp.maximum(cost, 1.0)) + math.log(253.0)) / safe_scale
    dist = jnp.where(used, dist, dist - inscribed)
    margin = c["collision_margin_distance"]
    raw = jnp.where(active & (dist < margin), margin - dist, 0.0).sum(axis=0)
    near_goal = within(data, c["near_goal_distance"])
    repulsive = jnp.where(active & ~near_goal, radius - dist, 0.0).sum(axis=0)
    collide = hit.any(axis=0)
    raw = jnp.where(collide, c["collision_cost"], raw)
    repulsive = (repulsive - repulsive.min()) / s.time_steps
    total = c["critical_weight"] * raw + c["repulsion_weight"] * repulsive
    return (total ** c["cost_power"] if c["cost_power"] > 1 else total), collide.all()


def goal(data: CriticData, c: Critic, s: Settings) -> Any:
    """GoalCritic: within threshold_to_consider of the goal, the mean distance to it."""
    d = jnp.hypot(data.x - data.goal[0], data.y - data.goal[1]).mean(axis=0)
    return jnp.where(within(data, c["threshold_to_consider"]), weighted(d, c), 0.0)


def goal_angle(data: CriticData, c: Critic, s: Settings) -> Any:
    """GoalAngleCritic: within threshold_to_consider, the mean heading error to the pruned
    plan's last pose (Nav2 1.3 reads the plan's, not the goal's, heading)."""
    heading = data.path[data.count - 1, 2]
    err = jnp.abs(normalize(heading - data.yaw)).mean(axis=0)
    return jnp.where(within(data, c["threshold_to_consider"]), weighted(err, c), 0.0)


def prefer_forward(data: CriticData, c: Critic, s: Settings) -> Any:
    """PreferForwardCritic: reverse speed integrated over time, until near the goal."""
    back = (jnp.maximum(-data.v.vx, 0.0) * s.model_dt).sum(axis=0)
    return jnp.where(within(data, c["threshold_to_consider"]), 0.0, weighted(back, c))


def twirling(data: CriticData, c: Critic, s: Settings) -> Any:
    """TwirlingCritic: the mean turn rate, until within the goal checker's tolerance."""
    turn = jnp.abs(data.v.wz).mean(axis=0)
    near = (data.goal_tolerance >= 0.0) & within(data, data.goal_tolerance)
    return jnp.where(near, 0.0, weighted(turn, c))


def path_follow(data: CriticData, c: Critic, s: Settings) -> Any:
    """PathFollowCritic: the rollouts' ends to the first free plan point offset_from_furthest
    beyond the furthest reached one."""
    last = data.count - 1
    start = jnp.minimum(data.furthest + c["offset_from_furthest"], last)
    index = jnp.arange(data.path.shape[0])
    free = data.valid & (index >= start) & (index < last - 1)
    target = jnp.where(start < last - 1, jnp.where(free.any(), jnp.argmax(free), last - 1), start)
    p = data.path[target]
    d = jnp.hypot(data.x[-1] - p[0], data.y[-1] - p[1])
    skip = (data.count < 2) | within(data, c["threshold_to_consider"])
    return jnp.where(skip, 0.0, weighted(d, c))


def path_angle(data: CriticData, c: Critic, s: Settings) -> Any:
    """PathAngleCritic: when the plan point offset_from_furthest ahead is more than
    max_angle_to_furthest off the robot's heading, the rollouts' final heading error to it
    (mode 0 forward, 1 either way, 2 the way the plan faces there)."""
    mode = c["mode"]
    if mode == 1 and not s.vx_min < -1e-6:
        mode = 0  # Nav2: no reversing, so forward preference
    target = data.path[jnp.minimum(data.furthest + c["offset_from_furthest"], data.count - 1)]
    px, py, pyaw = data.pose[0], data.pose[1], data.pose[2]
    bearing = jnp.arctan2(target[1] - py, target[0] - px)
    off = jnp.abs(normalize(pyaw - bearing))
    if mode == 1:
        off = jnp.minimum(off, jnp.abs(normalize(normalize(pyaw + PI) - bearing)))
    elif mode == 2:
        flipped = jnp.abs(normalize(target[2] - bearing)) > PI / 2
        off = jnp.abs(normalize(pyaw - jnp.where(flipped, normalize(bearing + PI), bearing)))
    towards = jnp.arctan2(target[1] - data.y[-1], target[0] - data.x[-1])
    final = data.yaw[-1]
    err = jnp.abs(normalize(towards - final))
    if mode == 1:
        towards = jnp.where(err < PI / 2, towards, normalize(towards + PI))
        err = jnp.abs(normalize(towards - final))
    elif mode == 2:
        ahead = jnp.abs(normalize(target[2] - towards)) < PI / 2
        towards = jnp.where(ahead, towards, normalize(towards + PI))
        err = jnp.abs(normalize(towards - final))
    skip = within(data, c["threshold_to_consider"]) | (off < c["max_angle_to_furthest"])
    return jnp.where(skip, 0.0, weighted(err, c))


def path_align(data: CriticData, c: Critic, s: Settings) -> Any:
    """PathAlignCritic: the mean distance from every trajectory_point_step-th pose to the
    plan point as far along the plan as the rollout has travelled, over free plan points up
    to the furthest reached; off when the rollouts reach fewer than offset_from_furthest
    points or too much of that plan is occupied."""
    segments = data.furthest
    index = jnp.arange(data.path.shape[0])
    invalid = (~data.valid & (index < segments)).sum().astype(jnp.float32)
    occupied = (invalid / jnp.maximum(segments, 1) > c["max_path_occupancy_ratio"]) & (
        invalid > 2.0
    )
    # the plan's integrated distance; points from the furthest on are out of reach
    seg = jnp.hypot(*(jnp.diff(data.path[:, :2], axis=0).T))
    along = jnp.concatenate([jnp.zeros(1), jnp.cumsum(seg)])
    along = jnp.where(index < segments, along, jnp.inf)
    step = c["trajectory_point_step"]
    tx, ty, tyaw = data.x[::step], data.y[::step], data.yaw[::step]
    travelled = running_sum(jnp.hypot(jnp.diff(tx, axis=0), jnp.diff(ty, axis=0)))
    # the nearest plan distance to each travelled one (ties and the end as Nav2's
    # findClosestPathPt), never going back along the plan
    above = _count_at_most(along, travelled)
    last = jnp.maximum(segments - 1, 0)
    lower = along[jnp.maximum(above - 1, 0)]
    upper = along[jnp.minimum(above, along.shape[0] - 1)]
    nearest = jnp.where(travelled - lower < upper - travelled, above - 1, above)
    nearest = jnp.where(above >= segments, last, nearest)
    nearest = _running_max(nearest)
    p = data.path[nearest]
    dx, dy = p[..., 0] - tx[1:], p[..., 1] - ty[1:]
    d2 = dx * dx + dy * dy
    if c["use_path_orientations"]:
        dyaw = normalize(tyaw[1:] - p[..., 2])
        d2 = d2 + dyaw * dyaw
    counted = data.valid[nearest]
    samples = counted.sum(axis=0)
    mean = jnp.where(counted, jnp.sqrt(d2), 0.0).sum(axis=0) / jnp.maximum(samples, 1)
    skip = (
        within(data, c["threshold_to_consider"]) | (segments < c["offset_from_furthest"]) | occupied
    )
    return jnp.where(skip, 0.0, weighted(mean, c))


def _running_max(values: Any) -> Any:
    """The running max along axis 0, a dozen steps unrolled: lax.cummax's reduce-window is
    slower on a CPU for so few."""
    out = [values[0]]
    for k in range(1, values.shape[0]):
        out.append(jnp.maximum(out[-1], values[k]))
    return jnp.stack(out)


def _count_at_most(sorted_values: Any, queries: Any) -> Any:
    """How many of ``sorted_values`` (P,) are at most each query: searchsorted's "right"
    index. A comparison per value, unrolled: on a CPU, 6x faster than searchsorted's binary
    search (a while loop of gathers) for the plan's few dozen points."""
    count = jnp.zeros(queries.shape, jnp.int32)
    for k in range(sorted_values.shape[0]):
        count = count + (sorted_values[k] <= queries).astype(jnp.int32)
    return count


#: critic name -> scoring function; those returning a pair also say "all rollouts collide"
CRITICS: dict[str, Callable[[CriticData, Critic, Settings], Any]] = {
    "ConstraintCritic": constraint,
    "CostCritic": cost_critic,
    "GoalCritic": goal,
    "GoalAngleCritic": goal_angle,
    "ObstaclesCritic": obstacles,
    "PathAlignCritic": path_align,
    "PathAngleCritic": path_angle,
    "PathFollowCritic": path_follow,
    "PreferForwardCritic": prefer_forward,
    "TwirlingCritic": twirling,
}
