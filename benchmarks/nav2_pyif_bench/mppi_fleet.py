"""Nav2MPPI for a fleet, batched: N robots' cycles in one ``compute_velocity_commands_batch``
call, paced at 20 Hz in this process (the planner's side of ``planner-host --batch``, without
Zenoh and the host's per-call work). Per N: the call's wall median and p99, the process's CPU
per robot-cycle (XLA's threads included), missed periods; that CPU against a C++ MPPI's
per-cycle figure times N; XLA's cost analysis of the batched step per robot and this
machine's copy bandwidth, the floor memory traffic sets."""

from __future__ import annotations

import argparse
import os
import time
from typing import Any

import numpy as np

PERIOD_S = 0.05


def _bandwidth_gb_s() -> float:
    """This machine's memory copy bandwidth: read + write of a 256 MB array, best of 5."""
    src = np.ones(32 * 2**20, np.float64)
    dst = np.empty_like(src)
    best = min(_seconds(np.copyto, dst, src) for _ in range(5))
    return 2 * src.nbytes / best / 1e9


def _seconds(fn: Any, *args: Any) -> float:
    started = time.perf_counter()
    fn(*args)
    return time.perf_counter() - started


def _fleet(n: int, rollouts: int) -> tuple[list[Any], Any]:
    """N Nav2MPPI robots (each its own costmap and plan, a little apart) and their batch."""
    from geometry_msgs.msg import Twist
    from nav2_pyif import Batch, GoalTolerances
    from nav2_pyif.runner.run import pose_msg

    from nav2_pyif_bench.mppi_cycle import configured_robot

    robots, poses = [], []
    for i in range(n):
        robot, plan = configured_robot(rollouts)
        robot.set_plan(plan)
        robots.append(robot)
        poses.append(pose_msg(10.0 + 0.01 * i, 0.2 * np.sin(2.5), 0.0))
    velocity = Twist()
    velocity.linear.x = 0.3
    checker = GoalTolerances(0.25, 0.25, 0.25, 0.25)
    return robots, Batch.of(robots, poses, [velocity] * n, [checker] * n)


def measure(n: int, rollouts: int, seconds: float, cost: bool) -> dict[str, Any]:
    """One fleet size paced at 20 Hz; ``cost``: XLA's cost analysis too (a compile more)."""
    from nav2_pyif_planners.mppi_nav2 import Nav2MPPI

    robots, batch = _fleet(n, rollouts)
    for _ in range(3):  # warm: XLA's first runs
        Nav2MPPI.compute_velocity_commands_batch(batch)
    walls, missed, cycles = [], 0, int(seconds / PERIOD_S)
    cpu_started, deadline = time.process_time(), time.perf_counter()
    for _ in range(cycles):
        started = time.perf_counter()
        out = Nav2MPPI.compute_velocity_commands_batch(batch)
        ended = time.perf_counter()
        walls.append(ended - started)
        deadline += PERIOD_S
        if ended > deadline:
            missed += 1
            deadline = ended  # the next period starts late
        else:
            time.sleep(deadline - ended)
    cpu = time.process_time() - cpu_started
    errors = [item for item in out if isinstance(item, Exception)]
    if errors:
        raise RuntimeError(f"a robot failed: {errors[0]!r}")
    wall_ms = np.array(walls) * 1e3
    return {
        "robots": n,
        "wall_median_ms": float(np.median(wall_ms)),
        "wall_p99_ms": float(np.percentile(wall_ms, 99)),
        "cpu_per_robot_cycle_ms": cpu / (cycles * n) * 1e3,
        "missed": missed,
        "cycles": cycles,
        "load": os.getloadavg()[0],
        "bytes_per_robot_mb": _bytes_per_robot(robots) if cost else None,
    }


def _bytes_per_robot(robots: list[Any]) -> float:
    """XLA's 'bytes accessed' of one robot's step (each robot of a fleet runs its own)."""
    from nav2_pyif_planners.mppi_nav2.optimizer import packed_step

    r = robots[0]
    packed = r.cycle_inputs(np.array([10.0, 0.1, 0.0]), _still(), None)
    lowered = packed_step.lower(
        r.sequence, r.history, r.bank, packed, r._upload_costmap(), s=r.settings
    )
    cost = lowered.compile().cost_analysis()
    cost = (cost[0] if isinstance(cost, list) else cost) or {}
    return float(cost.get("bytes accessed", 0.0)) / 1e6


def _still() -> Any:
    from geometry_msgs.msg import Twist

    return Twist()


def run(args: argparse.Namespace) -> dict[str, Any]:
    # bytes per robot barely change with N (the padded call): analysed at the first N only
    rows = [measure(n, args.rollouts, args.seconds, i == 0) for i, n in enumerate(args.robots)]
    return {
        "rollouts": args.rollouts,
        "cpp_ms": list(args.cpp_ms),
        "bandwidth_gb_s": _bandwidth_gb_s(),
        "rows": rows,
    }


def report(results: dict[str, Any]) -> str:
    cpp = results["cpp_ms"]
    lines = [
        f"Nav2MPPI batched, {results['rollouts']} x 56 per robot, 20 Hz; C++ MPPI per "
        f"robot-cycle: {' and '.join(f'{c:.2f}' for c in cpp)} ms; this machine copies "
        f"{results['bandwidth_gb_s']:.1f} GB/s",
        f"  {'robots':>6} {'load':>5} {'call median':>12} {'p99':>9} {'missed':>9} "
        f"{'CPU / robot-cycle':>18} {'vs C++':>13} {'XLA MB / robot':>15} {'floor':>9}",
    ]
    served = 0
    mb = results["rows"][0]["bytes_per_robot_mb"]
    for r in results["rows"]:
        cpu = r["cpu_per_robot_cycle_ms"]
        ratios = " / ".join(f"{cpu / c:.2f}x" for c in cpp)
        floor = mb / 1e3 / results["bandwidth_gb_s"] * 1e3
        lines.append(
            f"  {r['robots']:>6} {r['load']:>5.1f} {r['wall_median_ms']:>9.2f} ms "
            f"{r['wall_p99_ms']:>6.2f} ms {r['missed']:>4}/{r['cycles']:<4} {cpu:>15.2f} ms "
            f"{ratios:>13} {mb:>15.1f} {floor:>6.2f} ms"
        )
        if r["missed"] == 0:
            served = max(served, r["robots"])
    lines.append(f"largest fleet with no missed period: {served} robots")
    lines.append(
        f"floor: XLA's bytes accessed per robot (analysed at {results['rows'][0]['robots']} "
        "robots) at the copy bandwidth: memory traffic alone, were it all from DRAM"
    )
    return "\n".join(lines)
