"""Where Nav2MPPI's compiled step spends its time on this machine: the whole step, then each
part compiled and timed apart (the noise pick, the roll-out loops, the furthest plan point,
each critic, the update with its constraints and smoothing), and XLA's cost analysis of the
whole step (flops, bytes accessed). A synthetic cycle: a straight 1.7 m plan, a wall ahead,
the robot moving at 0.3 m/s; Nav2's default critics plus ObstaclesCritic, TwirlingCritic and
CostCritic with consider_footprint."""

from __future__ import annotations

import argparse
import logging
import os
import time
from collections.abc import Callable
from typing import Any

import numpy as np


def _timed(
    fn: Callable[..., Any], *args: Any, repeat: int, compiled: bool = False
) -> dict[str, float]:
    """Median and least time of ``fn`` on ``args``; compiled here (as the step is, with its
    compiler options) unless it already is."""
    import jax
    from nav2_pyif_planners.mppi_nav2.optimizer import jit_on

    if not compiled:
        fn = jit_on(jax.devices()[0].platform, fn)
    for _ in range(3):
        jax.block_until_ready(fn(*args))
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        jax.block_until_ready(fn(*args))
        times.append(time.perf_counter() - started)
    ms = np.array(times) * 1e3
    return {"median_ms": float(np.median(ms)), "min_ms": float(ms.min())}


def profile(rollouts: int, repeat: int) -> dict[str, Any]:
    import jax
    import jax.numpy as jnp
    from nav2_pyif import Parameters
    from nav2_pyif_planners.mppi_nav2.costs import Grid
    from nav2_pyif_planners.mppi_nav2.critics import CRITICS, CriticData
    from nav2_pyif_planners.mppi_nav2.models import Controls, roll_out
    from nav2_pyif_planners.mppi_nav2.optimizer import (
        Inputs,
        _iterate,
        furthest_reached,
        noise_bank,
        path_valid,
        step_on,
    )
    from nav2_pyif_planners.mppi_nav2.params import CRITIC_PARAMS, Critic, read_settings

    steps, points = 56, 56
    s = read_settings(
        Parameters({"batch_size": rollouts, "path_points": points}), 20.0, logging.getLogger("p")
    )
    rng = np.random.default_rng(0)
    bank = noise_bank(rng.standard_normal((8, 2, rollouts, steps), np.float32) * 0.2)
    cells = np.zeros((100, 100), np.uint8)
    cells[:, 70:] = 254
    rectangle = [[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]
    grid = Grid(
        jnp.asarray(cells),
        jnp.asarray([0.0, 0.0, 0.05], jnp.float32),
        jnp.asarray(rectangle, jnp.float32),
        jnp.asarray([50.0, 0.15, 0.55, 3.0], jnp.float32),
    )
    along = np.arange(0.5, 2.2, 0.05)
    path = np.zeros((points, 3), np.float32)
    path[: len(along), 0], path[:, 1] = along, 2.0
    path[len(along) :, 0] = along[-1]
    x = Inputs(
        pose=np.array([0.5, 2.0, 0.0], np.float32),
        speed=np.array([0.3, 0.0, 0.1], np.float32),
        goal=np.array([5.0, 2.0, 0.0], np.float32),
        limits=np.array([0.5, -0.35, 0.5, 1.9], np.float32),
        goal_tolerance=np.float32(0.25),
        path=path,
        count=np.int32(len(along)),
    )
    sequence = jnp.zeros((3, steps), jnp.float32).at[0].set(0.3)
    history = jnp.zeros((4, 3), jnp.float32)
    pick = np.array([1, 17], np.int32)
    parts: dict[str, Any] = {}
    platform = jax.devices()[0].platform
    step = step_on(platform)
    parts["whole step"] = _timed(
        lambda *a: step(*a, grid, s), sequence, history, bank, pick, x, repeat=repeat,
        compiled=True,
    )  # fmt: skip
    parts["noise pick and roll"] = _timed(
        lambda b, p: jax.lax.dynamic_slice_in_dim(b[p[0]], p[1], rollouts, axis=2),
        bank,
        pick,
        repeat=repeat,
    )
    noise = Controls(bank[1, 0, :, :rollouts], jnp.zeros(()), bank[1, 1, :, :rollouts])
    u = Controls(sequence[0], sequence[1], sequence[2])
    sampled = Controls(*(a[:, None] + n for a, n in zip(u, noise, strict=True)))
    parts["roll-out loops (limits, poses)"] = _timed(
        lambda c: roll_out(c, tuple(x.speed), tuple(x.pose), s), sampled, repeat=repeat
    )
    r = roll_out(sampled, tuple(x.speed), tuple(x.pose), s)
    parts["furthest plan point"] = _timed(
        lambda a, b: furthest_reached(a[-1], b[-1], jnp.asarray(path), x.count),
        r.x,
        r.y,
        repeat=repeat,
    )
    valid = path_valid(grid, jnp.asarray(path), x.count, s)
    data = CriticData(
        r.x, r.y, r.yaw, r.cos, r.sin, r.velocities, jnp.asarray(x.pose), jnp.asarray(x.goal),
        jnp.asarray(path), jnp.int32(x.count), valid,
        furthest_reached(r.x[-1], r.y[-1], jnp.asarray(path), x.count), grid,
        jnp.float32(0.25),
    )  # fmt: skip
    extra = [
        Critic("ObstaclesCritic", True, tuple(CRITIC_PARAMS["ObstaclesCritic"].items())),
        Critic("TwirlingCritic", True, tuple(CRITIC_PARAMS["TwirlingCritic"].items())),
        Critic(
            "CostCritic",
            True,
            tuple({**CRITIC_PARAMS["CostCritic"], "consider_footprint": True}.items()),
        ),
    ]
    for critic in (*s.critics, *extra):
        label = critic.name + (" (consider_footprint)" if critic in extra[2:] else "")
        parts[label] = _timed(lambda d, c=critic: CRITICS[c.name](d, c, s), data, repeat=repeat)
    on_device = Inputs(*(jnp.asarray(a) for a in x))
    parts["one iteration (all but smoothing)"] = _timed(
        lambda u, n: _iterate(u, n, on_device, grid, valid, s)[0], u, noise, repeat=repeat
    )
    lowered = step.lower(sequence, history, bank, pick, x, grid, s)
    cost = lowered.compile().cost_analysis()
    cost = (cost[0] if isinstance(cost, list) else cost) or {}
    return {
        "rollouts": rollouts,
        "time_steps": steps,
        "device": str(jax.devices()[0]),
        "jax": jax.__version__,
        "parts": parts,
        "flops_m": float(cost.get("flops", 0.0)) / 1e6,
        "bytes_accessed_mb": float(cost.get("bytes accessed", 0.0)) / 1e6,
    }


def run(args: argparse.Namespace) -> dict[str, Any]:
    from nav2_pyif_bench.mppi_cycle import cycle

    results: dict[str, Any] = {}
    for n in args.rollouts:
        results[str(n)] = {} if args.cycle_only else profile(n, args.repeat)
        timed = cycle(n, args.repeat, args.cold)
        results[str(n)].update(rollouts=n, cycle=timed, load=os.getloadavg()[0])
    return results


def report(results: dict[str, Any]) -> str:
    lines = []
    for r in results.values():
        lines.append(
            f"Nav2MPPI's whole cycle as the host runs it, {r['rollouts']} rollouts x 56 steps "
            f"(load average {r['load']:.1f}):"
        )
        lines.append(f"  {'part':<40} {'wall median':>12} {'wall p99':>10} {'CPU median':>11}")
        for name, t in r["cycle"].items():
            lines.append(
                f"  {name:<40} {t['wall_median_ms']:>9.3f} ms {t['wall_p99_ms']:>7.3f} ms "
                f"{t['cpu_median_ms']:>8.3f} ms"
            )
        if "parts" not in r:
            continue
        lines.append(
            f"Nav2MPPI's step, {r['rollouts']} rollouts x {r['time_steps']} steps on "
            f"{r['device']} (jax {r['jax']}): XLA cost analysis {r['flops_m']:.1f} Mflop, "
            f"{r['bytes_accessed_mb']:.1f} MB accessed"
        )
        lines.append(f"  {'part (compiled apart)':<40} {'median':>9} {'min':>9}")
        for name, t in r["parts"].items():
            lines.append(f"  {name:<40} {t['median_ms']:>6.3f} ms {t['min_ms']:>6.3f} ms")
    return "\n".join(lines)
