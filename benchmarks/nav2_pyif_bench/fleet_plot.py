"""The fleet benchmark drawn: latency and missed periods against the number of robots, so the
knee of one host on this machine is visible at a glance."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # files only, no display needed

import matplotlib.pyplot as plt


def plot_fleet(results: dict[str, Any], path: Path, machine: str) -> None:
    rows = sorted(results.values(), key=lambda r: r["robots"])
    robots = [r["robots"] for r in rows]
    fig, (latency, missed) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    latency.plot(robots, [r["median_ms"] for r in rows], "o-", label="median")
    latency.plot(robots, [r["p99_ms"] for r in rows], "s--", label="p99")
    latency.axhline(50.0, color="tab:red", lw=1, label="50 ms control period")
    latency.set(xlabel="robots at 20 Hz on one host", ylabel="round trip [ms]", yscale="log")
    latency.set_title("compute_velocity_commands latency")
    latency.legend()
    missed.bar([str(n) for n in robots], [r["missed_pct"] for r in rows], color="tab:red")
    for x, r in enumerate(rows):
        missed.annotate(f"{r['host_cpu_cores']:.2f} cores", (x, r["missed_pct"]),
                        ha="center", va="bottom", fontsize=8)  # fmt: skip
    missed.set(xlabel="robots", ylabel="missed periods [%]", ylim=(0, 105))
    missed.set_title("missed 50 ms periods (label: CPU of the host and its workers)")
    # fleet --isolation none runs every planner in the host process: no workers to name
    workers = "one worker per robot" if rows[0]["isolation"] == "process" else "no workers"
    fig.suptitle(f"one planner host, trivial planner, {workers}\n{machine}", fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
