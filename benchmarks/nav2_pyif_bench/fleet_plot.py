"""The fleet benchmark drawn: latency and missed periods against the number of robots, one
line per mode (one worker per robot, batched), so the knee of one host on this machine is
visible at a glance."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # files only, no display needed

import matplotlib.pyplot as plt


def plot_fleet(results: dict[str, Any], path: Path, machine: str) -> None:
    modes: dict[str, list[dict[str, Any]]] = {}
    for r in results.values():
        modes.setdefault(r["mode"], []).append(r)
    fig, (latency, missed) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    for n, (mode, rows) in enumerate(modes.items()):
        rows.sort(key=lambda r: r["robots"])
        robots = [r["robots"] for r in rows]
        color = f"C{n}"
        latency.plot(robots, [r["p99_ms"] for r in rows], "s-", color=color, label=f"{mode}: p99")
        latency.plot(robots, [r["median_ms"] for r in rows], "o:", color=color,
                     label=f"{mode}: median")  # fmt: skip
        missed.plot(robots, [r["missed_pct"] for r in rows], "o-", color=color, label=mode)
        for r in rows:
            missed.annotate(f"{r['host_cpu_cores']:.2f}", (r["robots"], r["missed_pct"]),
                            fontsize=7, ha="center", va="bottom", color=color)  # fmt: skip
    latency.axhline(50.0, color="tab:red", lw=1, label="50 ms control period")
    latency.set(xlabel="robots at 20 Hz on one host", ylabel="round trip [ms]", yscale="log")
    latency.set_title("compute_velocity_commands latency")
    latency.legend(fontsize=7)
    missed.set(xlabel="robots at 20 Hz on one host", ylabel="missed periods [%]", ylim=(-3, 105))
    missed.set_title("missed 50 ms periods (labels: host + workers CPU, cores)")
    missed.legend(fontsize=7)
    planner = next(iter(results.values()))["planner"] if results else "trivial"
    fig.suptitle(f"one planner host, {planner} controller\n{machine}", fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
