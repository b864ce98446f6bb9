"""Motion models (Nav2 MPPI's motion_models.hpp, in JAX): how sampled controls become the
velocities a rollout moves with, and how velocities become poses.

Velocities are (batch, steps) arrays, one per axis (vx, vy, wz): a trailing axis of 2 or 3
defeats XLA's vectorisation on a CPU."""

from __future__ import annotations

from typing import Any, NamedTuple

import jax
import jax.numpy as jnp

from nav2_pyif_planners.mppi_nav2.params import Settings


class Controls(NamedTuple):
    """Velocity commands per axis, each (..., steps) float32; vy is zeros unless Omni."""

    vx: Any
    vy: Any
    wz: Any


def clamp_step(value: Any, last: Any, low: float, high: float) -> Any:
    """Nav2's acceleration limit for one step of vx (or vy): ``low`` < 0 < ``high`` are the
    most change per step decelerating and accelerating, mirrored when ``last`` <= 0."""
    return jnp.where(
        last > 0, jnp.clip(value, last + low, last + high), jnp.clip(value, last - high, last - low)
    )


def accel_limited(controls: Controls, start: Controls, s: Settings) -> tuple[Controls, Controls]:
    """Nav2's MotionModel::predict over the batch: each control (batch, T) clamped to the
    acceleration limits from the velocity before it, starting from ``start`` (the robot's
    speed, per axis, scalars). -> (clamped controls, the rollouts' velocities: ``start`` then
    the clamped controls shifted by one step). The last control stays unclamped, as in Nav2
    (no velocity follows it)."""
    dt = s.model_dt
    lim_x = (dt * s.ax_min, dt * s.ax_max)
    lim_y = (dt * s.ay_min, dt * s.ay_max)
    dwz = dt * s.az_max

    def step(last: Any, u: Any) -> tuple[Any, Any]:
        vx = clamp_step(u[0], last[0], *lim_x)
        vy = clamp_step(u[1], last[1], *lim_y) if s.holonomic else u[1]
        wz = jnp.clip(u[2], last[2] - dwz, last[2] + dwz)
        return (vx, vy, wz), (vx, vy, wz)

    batch = controls.vx.shape[0]
    first = tuple(jnp.full((batch,), v, jnp.float32) for v in start)
    head = tuple(c.T[:-1] for c in controls)  # (T-1, batch): time-major for the scan
    _, clamped = jax.lax.scan(step, first, head, unroll=8)
    pairs = zip(clamped, controls, strict=True)
    new = Controls(*(jnp.concatenate([c.T, u[:, -1:]], axis=1) for c, u in pairs))
    velocities = Controls(
        *(jnp.concatenate([f[:, None], c.T], axis=1) for f, c in zip(first, clamped, strict=True))
    )
    return new, velocities


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


def running_sum(values: Any, dt: float) -> Any:
    """cumsum(values * dt) along the last axis (steps), as a product with a triangular
    matrix: XLA's cumsum on a CPU is a quadratic reduce-window, the matmul is BLAS."""
    steps = values.shape[-1]
    upper = jnp.triu(jnp.ones((steps, steps), jnp.float32))
    return jnp.matmul(values * dt, upper, precision=jax.lax.Precision.HIGHEST)


def integrate(v: Controls, pose: Any, s: Settings) -> tuple[Any, Any, Any]:
    """Rollout poses from velocities (batch, T) and the start ``pose`` (x, y, yaw): as Nav2's
    integrateStateVelocities, each step moves along the heading reached before it.
    -> x, y, yaw, each (batch, T)."""
    yaw = pose[2] + running_sum(v.wz, s.model_dt)
    before = jnp.concatenate([jnp.broadcast_to(pose[2], (*yaw.shape[:-1], 1)), yaw[..., :-1]], -1)
    c, sn = jnp.cos(before), jnp.sin(before)
    dx, dy = v.vx * c, v.vx * sn
    if s.holonomic:
        dx, dy = dx - v.vy * sn, dy + v.vy * c
    return pose[0] + running_sum(dx, s.model_dt), pose[1] + running_sum(dy, s.model_dt), yaw
