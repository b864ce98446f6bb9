"""The MPPI controllers through the real path: a planner host serving each over Zenoh, the
offline runner driving the bundled maps at 20 Hz, all at time_steps 56 x model_dt 0.05 (Nav2
MPPI's defaults). Per run: host compute and round trip per cycle, the host's CPU per cycle
(host and worker processes), time to goal and path length. The NumPy MPPI, the JAX MPPIJax
and the Nav2-compatible JAX Nav2MPPI (with Nav2 Jazzy's nav2_bringup FollowPath block, the
batch size overridden) side by side in one run."""

from __future__ import annotations

import argparse
import logging
import os
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import numpy as np
from nav2_pyif.runner.report import summary
from nav2_pyif.testing import drive

from nav2_pyif_bench.stats import verdict

TIME_STEPS = 56


def default_controllers() -> list[str]:
    jax = ["mppi_jax", "mppi_nav2"] if find_spec("jax") is not None else []
    return ["mppi", *jax]


def controller_params(controller: str, batch: int, time_steps: int) -> dict[str, Any]:
    if controller == "mppi_nav2":
        from nav2_pyif_planners.mppi_nav2 import nav2_jazzy_params

        return nav2_jazzy_params(batch_size=batch, time_steps=time_steps)
    return {"batch_size": batch, "time_steps": time_steps}


def _descendants_cpu() -> dict[int, float]:
    """utime + stime [s] of each live descendant of this process (the planner host and its
    worker), by pid, from /proc."""
    ticks = os.sysconf("SC_CLK_TCK")
    out: dict[int, float] = {}
    todo = [os.getpid()]
    while todo:
        pid = todo.pop()
        try:
            for task in Path(f"/proc/{pid}/task").iterdir():
                todo += [int(c) for c in (task / "children").read_text().split()]
            if pid != os.getpid():
                fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
                out[pid] = (int(fields[11]) + int(fields[12])) / ticks
        except (FileNotFoundError, ProcessLookupError):
            continue  # gone meanwhile
    return out


class _DrivingStarts(logging.Handler):
    """Notes the host's CPU when the runner starts driving (its "driving with" line): the
    planner configured and compiled, the cycles about to begin."""

    def __init__(self) -> None:
        super().__init__(logging.INFO)
        self.cpu_at_start: dict[int, float] | None = None

    def emit(self, record: logging.LogRecord) -> None:
        if "driving with" in record.getMessage():
            self.cpu_at_start = _descendants_cpu()


@contextmanager
def host_cpu() -> Iterator[dict[str, float]]:
    """Yields a dict that holds, after the block, ``cpu_s``: the CPU seconds the host's
    processes used from the first control cycle to their exit, each process's last sample
    (every 50 ms) counted."""
    out: dict[str, float] = {}
    marker = _DrivingStarts()
    logger = logging.getLogger("nav2_pyif.runner")
    level = logger.level
    logger.addHandler(marker)
    logger.setLevel(logging.INFO)
    last: dict[int, float] = {}
    done = threading.Event()

    def sample() -> None:
        while not done.wait(0.05):
            last.update(_descendants_cpu())

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    try:
        yield out
    finally:
        done.set()
        sampler.join()
        logger.removeHandler(marker)
        logger.setLevel(level)
    start = marker.cpu_at_start
    if start is not None:
        out["cpu_s"] = sum(cpu - start.get(pid, 0.0) for pid, cpu in last.items() if pid in start)


def run(args: argparse.Namespace) -> dict[str, Any]:
    results: dict[str, Any] = {}
    runs = [(c, b, m) for m in args.map for b in args.batch_sizes for c in args.controllers]
    for controller, batch, map_name in runs:
        print(f"  … {controller} with {batch} rollouts on the {map_name} map", flush=True)
        params = controller_params(controller, batch, args.time_steps)
        started = time.monotonic()
        with host_cpu() as cpu:
            result = drive(controller, map=map_name, controller_params=params, call_timeout=1.0)
        cycles = [r for r in result.records if r.op == "compute_velocity_commands" and r.ok]
        compute = np.array([r.compute_ns for r in cycles]) / 1e6
        total = np.array([r.total_ns for r in cycles]) / 1e6
        s = summary(result)
        results[f"{controller} {batch} {map_name}"] = {
            "controller": controller,
            "map": map_name,
            "rollouts": batch,
            "time_steps": args.time_steps,
            "reached": result.reached,
            "cycles": len(cycles),
            "compute_median_ms": float(np.median(compute)),
            "compute_p99_ms": float(np.percentile(compute, 99)),
            "round_trip_median_ms": float(np.median(total)),
            "round_trip_p99_ms": float(np.percentile(total, 99)),
            "max_rate_hz_at_p99": float(1000.0 / np.percentile(total, 99)),
            "host_cpu_per_cycle_ms": (
                1000.0 * cpu["cpu_s"] / len(cycles) if "cpu_s" in cpu and cycles else None
            ),
            "time_to_goal_s": s["sim_time_s"],
            "driven_m": s["driven_distance_m"],
            "plan_m": s["plan_length_m"],
            "wall_s": round(time.monotonic() - started, 1),
            "summary": s,
        }
    return results


def _maps_of(results: dict[str, Any]) -> str:
    return ", ".join(dict.fromkeys(str(r["map"]) for r in results.values())) or "?"


def report(results: dict[str, Any]) -> str:
    steps = {r.get("time_steps", "?") for r in results.values()}
    lines = [
        f"MPPI controllers through the planner host ({_maps_of(results)} map, 20 Hz, "
        f"time_steps {', '.join(map(str, sorted(steps, key=str)))})",
        f"  {'controller':>10} {'map':>9} {'rollouts':>8} {'compute median':>15} {'p99':>8} "
        f"{'round trip median':>18} {'p99':>8} {'rate at p99':>12} {'host CPU/cycle':>15} "
        f"{'time to goal':>13} {'driven':>8}  reached",
    ]
    for r in results.values():
        cpu = r.get("host_cpu_per_cycle_ms")
        lines.append(
            f"  {r['controller']:>10} {r['map']:>9} {r['rollouts']:>8} "
            f"{r['compute_median_ms']:>12.1f} ms {r['compute_p99_ms']:>5.1f} ms "
            f"{r['round_trip_median_ms']:>15.1f} ms {r['round_trip_p99_ms']:>5.1f} ms "
            f"{r['max_rate_hz_at_p99']:>9.0f} Hz "
            + (f"{cpu:>12.1f} ms " if cpu is not None else f"{'?':>15} ")
            + (
                f"{r['time_to_goal_s']:>11.1f} s {r['driven_m']:>6.1f} m  {r['reached']}"
                if "time_to_goal_s" in r
                else f"{'?':>13} {'?':>8}  {r['reached']}"
            )
        )
    lines += [f"  {line}" for line in target_lines(results)]
    return "\n".join(lines)


#: The target: this many rollouts per cycle at 20 Hz, i.e. a round trip p99 within a period.
TARGET_ROLLOUTS, TARGET_P99_MS = 1000, 50.0


def target_lines(results: dict[str, Any]) -> list[str]:
    """Per controller, a verdict on the target: its largest batch of at least
    TARGET_ROLLOUTS whose round trip p99 (as printed, one decimal) is within TARGET_P99_MS."""
    target = (
        f"target >= {TARGET_ROLLOUTS} rollouts at 20 Hz, round trip p99 <= {TARGET_P99_MS:g} ms"
    )
    lines = []
    for controller in dict.fromkeys(r["controller"] for r in results.values()):
        rows = [
            r
            for r in results.values()
            if r["controller"] == controller and r["rollouts"] >= TARGET_ROLLOUTS
        ]
        if not rows:
            lines.append(f"{controller}: no batch of >= {TARGET_ROLLOUTS} rollouts ({target}): ?")
            continue
        met = [r for r in rows if verdict(r["round_trip_p99_ms"], "<=", TARGET_P99_MS, 1) == "MET"]
        # the largest batch that meets it; else the one that came closest
        best = (
            max(met, key=lambda r: r["rollouts"])
            if met
            else min(rows, key=lambda r: r["round_trip_p99_ms"])
        )
        lines.append(
            f"{controller}: {best['rollouts']} rollouts, round trip p99 "
            f"{best['round_trip_p99_ms']:.1f} ms ({target}): {'MET' if met else 'NOT MET'}"
        )
    return lines
