"""Nav2 MPPI's optimizer (optimizer.cpp, Jazzy) as one jit-compiled function: sample noised
controls around the optimal sequence, limit their accelerations as the motion model does,
roll them out, score them with the critics, move the sequence to the softmin-weighted mean,
constrain it, smooth it (Savitzky-Golay), take the command and shift the sequence for the
next cycle's warm start.

All of it runs on the device in one call per cycle: float32, static shapes (batch, steps,
plan points, costmap size), the settings a static argument (compiled at configure). The only
inputs that change per cycle are small arrays (pose, speed, plan, the sequence); the costmap
is uploaded once per costmap version and the noise bank once per configure.

Noise: Nav2 draws it with xtensor's generator, once per reset (regenerate_noises: false) or
on a thread each cycle (true). Drawing 2 x batch x steps normals with JAX's counter-based
PRNG costs more on a CPU than the rest of the cycle (measured: 6 ms for 2000 x 56 x 3 on this
2-core VM), so the controller draws a bank of noise sets at configure and each cycle uses
one set, rolled along the batch by a random offset (regenerate_noises: true). With
regenerate_noises false, the set stays the same, unrolled, until a reset takes the bank's
next one, as Nav2 draws new noise on each reset (a goal ended, a fallback)."""

from __future__ import annotations

from functools import cache, partial
from typing import Any, NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

from nav2_pyif_planners.mppi_nav2.costs import INSCRIBED, LETHAL, NO_INFORMATION, Grid, point_cost
from nav2_pyif_planners.mppi_nav2.critics import CRITICS, CriticData
from nav2_pyif_planners.mppi_nav2.models import Controls, constrain_sequence, roll_out
from nav2_pyif_planners.mppi_nav2.params import Settings
from nav2_pyif_planners.mppi_nav2.smoothing import smooth


class Inputs(NamedTuple):
    """One cycle's inputs, float32 unless said: ``pose`` (x, y, yaw), ``speed`` (vx, vy,
    wz), ``goal`` (x, y, yaw), ``limits`` (vx_max, vx_min, vy_max, wz_max after any speed
    limit), ``goal_tolerance`` (the goal checker's xy tolerance, -1 without one), ``path``
    (P, 3) the pruned plan padded with its last pose, ``count`` int32 its length."""

    pose: Any
    speed: Any
    goal: Any
    limits: Any
    goal_tolerance: Any
    path: Any
    count: Any


class Outputs(NamedTuple):
    """``sequence`` (3, T) the next cycle's warm start (shifted when Nav2 would),
    ``history`` (4, 3) the last four commands, ``reply`` (vx, vy, wz, fail): the command and
    1.0 when every rollout collided (Nav2's fail_flag), ``optimal`` (3, T) the smoothed
    sequence before the shift (the local_plan debug output)."""

    sequence: Any
    history: Any
    reply: Any
    optimal: Any


def path_valid(grid: Grid, path: Any, count: Any, s: Settings) -> Any:
    """Nav2's path_pts_valid over the plan's segments (its points but the last): off the map,
    lethal or inscribed is not valid; unknown is when the costmap tracks unknown space."""
    cost = point_cost(grid, path[:, 0], path[:, 1])
    bad = (cost == LETHAL) | (cost == INSCRIBED)
    bad = bad | ((cost == NO_INFORMATION) & (not s.track_unknown_space))
    return ~bad & (jnp.arange(path.shape[0]) < count - 1)


def furthest_reached(x_end: Any, y_end: Any, path: Any, count: Any) -> Any:
    """The furthest plan index that is the nearest one to some rollout's end. Nav2 scans the
    rollouts in order, each searching only from the furthest index so far; this takes the
    most of every rollout's nearest index, which is the same unless the plan comes back near
    itself within the horizon."""
    # argmin by a comparison per plan point, unrolled over the few dozen points: on a CPU,
    # 3x faster than XLA's reduce over the (batch, points) distances, and the first index
    # of the least distance wins, as Nav2's strict less-than does
    best = jnp.full(x_end.shape, jnp.inf, jnp.float32)
    nearest = jnp.zeros(x_end.shape, jnp.int32)
    for k in range(path.shape[0]):
        dx, dy = x_end - path[k, 0], y_end - path[k, 1]
        d2 = jnp.where(k < count, dx * dx + dy * dy, jnp.inf)
        closer = d2 < best
        nearest = jnp.where(closer, k, nearest)
        best = jnp.where(closer, d2, best)
    return nearest.max()


#: float32 products at full precision: GPUs would otherwise use TF32 (10-bit mantissa)
dot = partial(jnp.matmul, precision=jax.lax.Precision.HIGHEST)


def _score(data: CriticData, s: Settings) -> tuple[Any, Any]:
    costs = jnp.zeros(data.x.shape[1], jnp.float32)
    fail = jnp.asarray(False)
    for critic in s.critics:
        if not critic.enabled:
            continue
        out = CRITICS[critic.name](data, critic, s)
        if isinstance(out, tuple):
            out, collide = out
            fail = fail | collide
        costs = costs + out
    return costs, fail


def _iterate(
    u: Controls, noise: Controls, x: Inputs, grid: Grid, valid: Any, s: Settings
) -> tuple[Controls, Any]:
    """One Nav2 iteration: generateNoisedTrajectories, the critics, updateControlSequence."""
    sampled = Controls(*(a[:, None] + n for a, n in zip(u, noise, strict=True)))
    r = roll_out(sampled, tuple(x.speed), tuple(x.pose), s)
    clamped = r.controls
    data = CriticData(
        x=r.x, y=r.y, yaw=r.yaw, cos=r.cos, sin=r.sin, v=r.velocities, pose=x.pose,
        goal=x.goal, path=x.path, count=x.count, valid=valid,
        furthest=furthest_reached(r.x[-1], r.y[-1], x.path, x.count), grid=grid,
        goal_tolerance=x.goal_tolerance,
    )  # fmt: skip
    costs, fail = _score(data, s)
    axes = [(u.vx, clamped.vx, s.vx_std), (u.wz, clamped.wz, s.wz_std)]
    if s.holonomic:
        axes.append((u.vy, clamped.vy, s.vy_std))
    for mean, c, std in axes:
        costs = costs + s.gamma / std**2 * dot(mean, c - mean[:, None])
    weights = jax.nn.softmax(-(costs - costs.min()) / s.temperature)
    lateral = dot(clamped.vy, weights) if s.holonomic else jnp.zeros_like(u.vx)
    new = Controls(dot(clamped.vx, weights), lateral, dot(clamped.wz, weights))
    return constrain_sequence(new, s, x.limits), fail


def noise_bank(draw: np.ndarray, device: Any = None) -> Any:
    """The noise bank on ``device`` (JAX's default: None) from ``draw`` (sets, axes, batch,
    T), already scaled: each set time-major, as the step reads it, and laid twice along the
    batch, so that a set rolled by any offset is one window of it."""
    time_major = np.ascontiguousarray(draw.transpose(0, 1, 3, 2), np.float32)
    return jax.device_put(np.concatenate([time_major, time_major], axis=3), device)


def _step(
    sequence: Any,
    history: Any,
    bank: Any,
    pick: Any,
    x: Inputs,
    grid: Grid,
    s: Settings,
) -> Outputs:
    """One control cycle. ``sequence`` (3, T) vx, vy, wz; ``history`` (4, 3); ``bank``
    (``noise_bank``) the noise sets, scaled by the sigmas; ``pick`` int32 (set, roll)."""
    batch = bank.shape[-1] // 2
    # a set rolled along the batch by pick[1]: the window of the set laid twice, which
    # XLA reads in the sum with the sequence instead of copying a rolled set first
    offset = (batch - pick[1]) % batch
    drawn = jax.lax.dynamic_slice_in_dim(bank[pick[0]], offset, batch, axis=2)
    lateral = drawn[1] if s.holonomic else jnp.zeros((), jnp.float32)
    noise = Controls(drawn[0], lateral, drawn[-1])
    valid = path_valid(grid, x.path, x.count, s)
    u = Controls(sequence[0], sequence[1], sequence[2])
    fail = jnp.asarray(False)
    for _ in range(s.iteration_count):
        u, fail = _iterate(u, noise, x, grid, valid, s)
    u = Controls(*(smooth(a, history[:, i]) for i, a in enumerate(u)))
    optimal = jnp.stack(list(u))
    offset = 1 if s.shift_control_sequence else 0
    command = optimal[:, offset]
    history = jnp.concatenate([history[1:], command[None, :]])
    if s.shift_control_sequence:
        sequence = jnp.concatenate([optimal[:, 1:], optimal[:, -1:]], axis=1)
    else:
        sequence = optimal
    # the command and the flag in one array: one transfer to the host per cycle, not two
    reply = jnp.concatenate([command, fail.astype(jnp.float32)[None]])
    return Outputs(sequence, history, reply, optimal)


#: XLA's CPU options for the step: no YNNPACK fusions. YNNPACK takes each critic's masked
#: sum as a kernel of its own, fed by (T, batch) arrays of zeros that XLA must first fill;
#: without it the sums fuse with what they read. The step alone (a one-off probe, BENCHMARKS.md
#: "Cold calls"): 0.1 ms faster back to back, 0.35 ms faster with the caches flushed first.
CPU_OPTIONS = {"xla_cpu_experimental_ynn_fusion_type": ""}


@cache
def compiler_options(platform: str) -> tuple[tuple[str, str], ...]:
    """CPU_OPTIONS on a CPU whose XLA takes them; none elsewhere (XLA's defaults)."""
    if platform != "cpu":
        return ()
    try:
        probe = jax.device_put(np.float32(0), jax.devices("cpu")[0])
        jax.jit(lambda v: v + 1, compiler_options=CPU_OPTIONS).lower(probe).compile()
    except Exception:  # an older JAX or XLA: no such option, or no compiler_options
        return ()
    return tuple(CPU_OPTIONS.items())


def jit_on(platform: str, fn: Any, **kwargs: Any) -> Any:
    """``jax.jit(fn)`` with this platform's compiler_options."""
    options = compiler_options(platform)
    if options:
        kwargs["compiler_options"] = dict(options)
    return jax.jit(fn, **kwargs)


@cache
def step_on(platform: str) -> Any:
    """The step (``_step``) compiled for a platform ("cpu", "gpu", ...)."""
    return jit_on(platform, _step, static_argnames=("s",))


#: rows of a packed cycle array before the plan's: pose, speed, goal, limits (vx_max, vx_min,
#: vy_max), (wz_max, goal_tolerance, count), (noise set, roll, unused)
HEADER = 6


def pack(
    pose: Any, speed: Any, goal: Any, limits: Any, goal_tolerance: float, path: Any, count: int
) -> np.ndarray:
    """A cycle's inputs in one float32 (HEADER + P, 3) array: one transfer to the device
    and one argument to dispatch, not eight (measured: 54 against 9 us of dispatch). Its
    noise pick (row 5) is filled in by the caller."""
    out = np.zeros((HEADER + len(path), 3), np.float32)
    out[0], out[1], out[2], out[3] = pose, speed, goal, limits[:3]
    out[4] = limits[3], goal_tolerance, count
    out[HEADER:] = path
    return out


def unpack(packed: Any) -> tuple[Any, Inputs]:
    """(pick, Inputs) from a packed cycle array, inside the compiled step."""
    limits = jnp.concatenate([packed[3], packed[4, :1]])
    count = packed[4, 2].astype(jnp.int32)
    x = Inputs(packed[0], packed[1], packed[2], limits, packed[4, 1], packed[HEADER:], count)
    return packed[5, :2].astype(jnp.int32), x


def _packed_step(
    sequence: Any, history: Any, bank: Any, packed: Any, grid: Grid, s: Settings
) -> Outputs:
    pick, x = unpack(packed)
    return _step(sequence, history, bank, pick, x, grid, s)


@cache
def packed_step_on(platform: str) -> Any:
    """The step on a packed cycle array (``pack``), compiled for a platform: what the
    controller runs each cycle."""
    return jit_on(platform, _packed_step, static_argnames=("s",))
