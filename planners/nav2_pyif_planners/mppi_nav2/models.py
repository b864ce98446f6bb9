"""Motion models (Nav2 MPPI's motion_models.hpp, in JAX): how sampled controls become the
velocities a rollout moves with, and how velocities become poses.

Velocities are (steps, batch) arrays, one per axis (vx, vy, wz): a trailing axis of 2 or 3
defeats XLA's vectorisation on a CPU, and time-major rows are what a scan over the steps
reads and writes without a transpose."""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import jax
import jax.numpy as jnp

from nav2_pyif_planners.mppi_nav2.params import Settings


class Controls(NamedTuple):
    """Velocity commands per axis, each (steps, ...) float32; vy is zeros unless Omni."""

    vx: Any
    vy: Any
    wz: Any


def clamp_step(value: Any, last: Any, low: float, high: float) -> Any:
    """Nav2's acceleration limit for one step of vx (or vy): ``low`` < 0 < ``high`` are the
    most change per step decelerating and accelerating, mirrored when ``last`` <= 0."""
    return jnp.where(
        last > 0, jnp.clip(value, last + low, last + high), jnp.clip(value, last - high, last - low)
    )


TWO_PI = 2.0 * math.pi


def cos_sin(angle: Any) -> tuple[Any, Any]:
    """cos and sin of float32 angles by multiplications and additions alone: reduced to
    [-pi, pi], Taylor series at a quarter of it, then two double-angle steps. Within 4e-7 of
    the libm values; on a CPU, XLA's cos and sin of a (56, 1000) array take 1 ms, this a
    tenth of it."""
    quarter = (angle - TWO_PI * jnp.round(angle * (1.0 / TWO_PI))) * 0.25
    q2 = quarter * quarter
    c = 1.0 + q2 * (-1.0 / 2 + q2 * (1.0 / 24 + q2 * (-1.0 / 720 + q2 * (1.0 / 40320))))
    s = quarter * (
        1.0 + q2 * (-1.0 / 6 + q2 * (1.0 / 120 + q2 * (-1.0 / 5040 + q2 * (1.0 / 362880))))
    )
    for _ in range(2):
        c, s = c * c - s * s, 2.0 * s * c
    return c, s


class Rollouts(NamedTuple):
    """The sampled controls after the acceleration limits (T, batch) per axis, the
    velocities each rollout moved with (the robot's speed first), and its poses after each
    step, x, y, yaw (T, batch), with the heading's cos and sin (the footprint's rotation)."""

    controls: Controls
    velocities: Controls
    x: Any
    y: Any
    yaw: Any
    cos: Any
    sin: Any


def running_sum(steps: Any, start: Any = 0) -> Any:
    """``start`` plus the running sum of ``steps`` along axis 0, added in order. The sums
    overwrite ``steps`` row by row in one loop: a scan would first fill a zeroed array for its
    outputs (a whole extra pass through memory, the slowest part of a cold cycle), and XLA's
    cumsum is a reduce-window, slower still on a CPU."""
    first = steps[0] + start
    out = jax.lax.dynamic_update_index_in_dim(steps, first.astype(steps.dtype), 0, 0)

    def add(t: Any, rows: Any) -> Any:
        total = jax.lax.dynamic_index_in_dim(rows, t - 1, keepdims=False)
        step = jax.lax.dynamic_index_in_dim(rows, t, keepdims=False)
        return jax.lax.dynamic_update_index_in_dim(rows, total + step, t, 0)

    return jax.lax.fori_loop(1, steps.shape[0], add, out)


def roll_out(controls: Controls, speed: Any, pose: Any, s: Settings) -> Rollouts:
    """Nav2's MotionModel::predict and integrateStateVelocities: each control (T, batch)
    clamped to the acceleration limits from the velocity before it, starting from ``speed``
    (vx, vy, wz), and each pose moved from ``pose`` (x, y, yaw) with that velocity along the
    heading reached before it. The last control stays unclamped, as in Nav2 (no velocity
    follows it). Time-major, so that the loops read and write whole rows: the limits in one
    loop, the headings in a second (``running_sum``), their cos and sin at once
    (``cos_sin``), the positions in two more. Each loop overwrites the array it reads; none
    fills a zeroed one first (a cold cycle pays most for passes through memory)."""
    dt = s.model_dt
    lim_x = (dt * s.ax_min, dt * s.ax_max)
    lim_y = (dt * s.ay_min, dt * s.ay_max)
    dwz = dt * s.az_max
    batch = controls.vx.shape[1]
    # DiffDrive and Ackermann have no lateral velocity: no (T, batch) vy array is moved
    axes = (0, 1, 2) if s.holonomic else (0, 2)

    def limit(t: Any, carry: Any) -> Any:
        rows, last = carry
        new = []
        for axis, row, before in zip(axes, rows, last, strict=True):
            now = jax.lax.dynamic_index_in_dim(row, t, keepdims=False)
            if axis == 2:
                new.append(jnp.clip(now, before - dwz, before + dwz))
            else:
                new.append(clamp_step(now, before, *(lim_x if axis == 0 else lim_y)))
        rows = tuple(
            jax.lax.dynamic_update_index_in_dim(r, n, t, 0) for r, n in zip(rows, new, strict=True)
        )
        return rows, tuple(new)

    start = tuple(jnp.full((batch,), speed[a], jnp.float32) for a in axes)
    sampled = tuple(controls[a] for a in axes)
    # row t of each sampled control becomes the velocity it leads to, in place
    steps = controls.vx.shape[0]
    limited, _ = jax.lax.fori_loop(0, steps - 1, limit, (sampled, start))
    moved = [jnp.concatenate([v[None], c[:-1]]) for v, c in zip(start, limited, strict=True)]
    if not s.holonomic:
        zeros = jnp.zeros_like(controls.vx)
        limited, moved = (limited[0], zeros, limited[1]), [moved[0], zeros, moved[1]]
    clamped, velocities = Controls(*limited), Controls(*moved)

    yaw = running_sum(velocities.wz * dt, pose[2])
    cos, sin = cos_sin(yaw)
    # each step moves along the heading before it: the robot's own, then the rollout's
    own = cos_sin(jnp.full((1, batch), pose[2], jnp.float32))
    before_cos = jnp.concatenate([own[0], cos[:-1]])
    before_sin = jnp.concatenate([own[1], sin[:-1]])
    vx, vy = velocities.vx, velocities.vy
    dx, dy = vx * before_cos, vx * before_sin
    if s.holonomic:
        dx, dy = dx - vy * before_sin, dy + vy * before_cos
    x = running_sum(dx * dt, pose[0])
    y = running_sum(dy * dt, pose[1])
    return Rollouts(clamped, velocities, x, y, yaw, cos, sin)


def constrain_sequence(u: Controls, s: Settings, limits: Any) -> Controls:
    """Nav2's applyControlSequenceConstraints on the optimal sequence (T,): speed limits
    (``limits``: vx_max, vx_min, vy_max, wz_max after any speed limit), acceleration limits
    from its first step on, and Ackermann's minimum turning radius."""
    vx = jnp.clip(u.vx, limits[1], limits[0])
    vy = jnp.clip(u.vy, -limits[2], limits[2]) if s.holonomic else u.vy
    wz = jnp.clip(u.wz, -limits[3], limits[3])
    dt = s.model_dt

    def step(last: tuple[Any, Any, Any], c: tuple[Any, Any, Any]) -> tuple[Any, Any]:
        nx = clamp_step(c[0], last[0], dt * s.ax_min, dt * s.ax_max)
        ny = clamp_step(c[1], last[1], dt * s.ay_min, dt * s.ay_max) if s.holonomic else c[1]
        nz = jnp.clip(c[2], last[2] - dt * s.az_max, last[2] + dt * s.az_max)
        return (nx, ny, nz), (nx, ny, nz)

    first = (vx[0], vy[0], wz[0])
    _, rest = jax.lax.scan(step, first, (vx[1:], vy[1:], wz[1:]))
    out = Controls(*(jnp.concatenate([f[None], r]) for f, r in zip(first, rest, strict=True)))
    if s.motion_model == "Ackermann":
        # |vx| / |wz| below the minimum radius: turn no tighter than it allows
        tight = jnp.abs(out.vx) / jnp.abs(out.wz) < s.min_turning_r
        out = out._replace(
            wz=jnp.where(tight, jnp.sign(out.wz) * jnp.abs(out.vx) / s.min_turning_r, out.wz)
        )
    return out
