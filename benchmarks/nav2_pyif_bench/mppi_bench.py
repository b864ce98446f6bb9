"""The MPPI controller's rate through the real path: a planner host serving it over Zenoh,
the offline runner driving the office map at 20 Hz; host compute and round trip per cycle.
The NumPy MPPI and the JAX one (when JAX is installed) side by side."""

from __future__ import annotations

import argparse
from importlib.util import find_spec
from typing import Any

import numpy as np
from nav2_pyif.runner.report import summary
from nav2_pyif.testing import drive

from nav2_pyif_bench.stats import verdict


def default_controllers() -> list[str]:
    return ["mppi", "mppi_jax"] if find_spec("jax") is not None else ["mppi"]


def run(args: argparse.Namespace) -> dict[str, Any]:
    results: dict[str, Any] = {}
    runs = [(c, b) for b in args.batch_sizes for c in args.controllers]
    for controller, batch in runs:
        print(f"  … {controller} with {batch} rollouts on the {args.map} map", flush=True)
        result = drive(
            controller, map=args.map, controller_params={"batch_size": batch}, call_timeout=1.0
        )
        cycles = [r for r in result.records if r.op == "compute_velocity_commands" and r.ok]
        compute = np.array([r.compute_ns for r in cycles]) / 1e6
        total = np.array([r.total_ns for r in cycles]) / 1e6
        results[f"{controller} {batch}"] = {
            "controller": controller,
            "map": args.map,
            "rollouts": batch,
            "reached": result.reached,
            "cycles": len(cycles),
            "compute_median_ms": float(np.median(compute)),
            "compute_p99_ms": float(np.percentile(compute, 99)),
            "round_trip_median_ms": float(np.median(total)),
            "round_trip_p99_ms": float(np.percentile(total, 99)),
            "max_rate_hz_at_p99": float(1000.0 / np.percentile(total, 99)),
            "summary": summary(result),
        }
    return results


def _map_of(results: dict[str, Any]) -> str:
    return str(next(iter(results.values()))["map"]) if results else "?"


def report(results: dict[str, Any]) -> str:
    lines = [
        f"MPPI controllers through the planner host ({_map_of(results)} map, 20 Hz, time_steps 40)",
        f"  {'controller':>10} {'rollouts':>8} {'compute median':>15} {'p99':>8} "
        f"{'round trip median':>18} {'p99':>8} {'rate at p99':>12}  reached",
    ]
    for r in results.values():
        lines.append(
            f"  {r['controller']:>10} {r['rollouts']:>8} {r['compute_median_ms']:>12.1f} ms "
            f"{r['compute_p99_ms']:>5.1f} ms "
            f"{r['round_trip_median_ms']:>15.1f} ms {r['round_trip_p99_ms']:>5.1f} ms "
            f"{r['max_rate_hz_at_p99']:>9.0f} Hz  {r['reached']}"
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
