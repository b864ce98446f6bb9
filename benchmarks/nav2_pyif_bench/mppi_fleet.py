"""Nav2MPPI for a fleet, batched: N robots' cycles in one ``compute_velocity_commands_batch``
call, paced at 20 Hz in this process (the planner's side of ``planner-host --batch``, without
Zenoh and the host's per-call work). Per N: the call's wall median and p99, the process's CPU
per robot-cycle (XLA's threads included), missed periods; that CPU against a C++ MPPI's
per-cycle figure times N; XLA's cost analysis of the batched step per robot and this
machine's copy bandwidth, the floor memory traffic sets.

``--lanes 1 2``: the robots on that many JAX CPU devices each (Nav2MPPI's lanes.py takes one
per core), side by side: a process per lane count (JAX fixes its device count once per
process), the lane counts interleaved in rounds, each fleet size's figures pooled over the
rounds."""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
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
    from nav2_pyif_planners.mppi_nav2.optimizer import packed_step_on

    r = robots[0]
    packed = r.cycle_inputs(np.array([10.0, 0.1, 0.0]), _still(), None)
    lowered = packed_step_on(r.device.platform).lower(
        r.sequence, r.history, r.bank, packed, r._upload_costmap(), s=r.settings
    )
    cost = lowered.compile().cost_analysis()
    cost = (cost[0] if isinstance(cost, list) else cost) or {}
    return float(cost.get("bytes accessed", 0.0)) / 1e6


def _still() -> Any:
    from geometry_msgs.msg import Twist

    return Twist()


def _rows(robots: list[int], rollouts: int, seconds: float) -> list[dict[str, Any]]:
    # bytes per robot do not change with N (each robot its own step): analysed at the first N
    return [measure(n, rollouts, seconds, i == 0) for i, n in enumerate(robots)]


#: a child of ``--lanes``: argv lanes, rollouts, seconds, robots...; prints its rows as JSON
CHILD = """
import json, sys
import jax
jax.config.update("jax_num_cpu_devices", int(sys.argv[1]))
from nav2_pyif_bench.mppi_fleet import _rows
robots = [int(n) for n in sys.argv[4:]]
print(json.dumps(_rows(robots, int(sys.argv[2]), float(sys.argv[3]))))
"""


def _lanes(args: argparse.Namespace) -> list[dict[str, Any]]:
    """Each lane count in its own process, the counts interleaved over ``args.rounds``; per lane
    count and fleet size: the medians of the rounds' figures, missed periods summed."""
    runs: dict[int, list[list[dict[str, Any]]]] = {lanes: [] for lanes in args.lanes}
    for _ in range(args.rounds):
        for lanes in args.lanes:
            argv = [str(v) for v in (lanes, args.rollouts, args.seconds, *args.robots)]
            out = subprocess.run(
                [sys.executable, "-c", CHILD, *argv], capture_output=True, text=True, check=True
            )
            runs[lanes].append(json.loads(out.stdout.strip().splitlines()[-1]))
    rows = []
    for lanes, rounds in runs.items():
        for per_size in zip(*rounds, strict=True):
            row = dict(per_size[0], lanes=lanes, rounds=len(per_size))
            for key in ("wall_median_ms", "wall_p99_ms", "cpu_per_robot_cycle_ms", "load"):
                row[key] = float(np.median([r[key] for r in per_size]))
            row["missed"] = sum(r["missed"] for r in per_size)
            row["cycles"] = sum(r["cycles"] for r in per_size)
            rows.append(row)
    return rows


def run(args: argparse.Namespace) -> dict[str, Any]:
    one_process = not getattr(args, "lanes", None)
    rows = _rows(args.robots, args.rollouts, args.seconds) if one_process else _lanes(args)
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
        f"  {'lanes':>5} {'robots':>6} {'load':>5} {'call median':>12} {'p99':>9} {'missed':>9} "
        f"{'CPU / robot-cycle':>18} {'vs C++':>13} {'XLA MB / robot':>15} {'floor':>9}",
    ]
    served: dict[Any, int] = {}
    mb = results["rows"][0]["bytes_per_robot_mb"]
    for r in results["rows"]:
        cpu, lanes = r["cpu_per_robot_cycle_ms"], r.get("lanes", "auto")
        ratios = " / ".join(f"{cpu / c:.2f}x" for c in cpp)
        floor = mb / 1e3 / results["bandwidth_gb_s"] * 1e3
        lines.append(
            f"  {lanes:>5} {r['robots']:>6} {r['load']:>5.1f} "
            f"{r['wall_median_ms']:>9.2f} ms "
            f"{r['wall_p99_ms']:>6.2f} ms {r['missed']:>4}/{r['cycles']:<4} {cpu:>15.2f} ms "
            f"{ratios:>13} {mb:>15.1f} {floor:>6.2f} ms"
        )
        if r["missed"] == 0:
            served[lanes] = max(served.get(lanes, 0), r["robots"])
    for lanes, robots in served.items():
        lanes_text = "" if lanes == "auto" else f" on {lanes} lane(s)"
        lines.append(f"largest fleet with no missed period{lanes_text}: {robots} robots")
    if results["rows"][0].get("rounds"):
        lines.append(
            f"each row: the medians of {results['rows'][0]['rounds']} interleaved rounds, "
            "missed periods summed over them"
        )
    lines.append(
        f"floor: XLA's bytes accessed per robot (analysed at {results['rows'][0]['robots']} "
        "robots) at the copy bandwidth: memory traffic alone, were it all from DRAM"
    )
    return "\n".join(lines)
