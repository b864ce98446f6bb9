"""The report of ``nav2-pyif eval``: a row per planner over every scenario (printed, and as
JSON and CSV), every run's row, and a summary plot."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from nav2_pyif.evaluation.metrics import COMPUTE_FIELDS, DIGITS

#: The summary's columns: (key, heading, format).
COLUMNS = (
    ("planner", "planner", "{}"),
    ("runs", "runs", "{:d}"),
    ("success_rate", "success", "{:.0%}"),
    ("time_to_goal_s", "time s", "{:.1f}"),
    ("path_length_m", "path m", "{:.2f}"),
    ("min_clearance_m", "min clear m", "{:.3f}"),
    ("jerk_rms", "jerk m/s³", "{:.1f}"),
    ("barn_score", "BARN", "{:.3f}"),
    ("compute_median_ms", "compute med ms", "{:.2f}"),
    ("compute_p99_ms", "compute p99 ms", "{:.2f}"),
    ("compute_p99_of_period", "p99/period", "{:.0%}"),
)


def _mean(values: list[Any]) -> float | None:
    kept = [float(v) for v in values if v is not None]
    return round(float(np.mean(kept)), DIGITS) if kept else None


def _present(runs: list[dict[str, Any]], key: str) -> list[float]:
    """The runs' ``key`` figures, less the runs that have none."""
    return [float(r[key]) for r in runs if r.get(key) is not None]


def summarize(rows: list[dict[str, Any]], planners: list[str]) -> list[dict[str, Any]]:
    """Per planner: success rate; means over its successful runs of time to goal and path
    length, over all runs of jerk and BARN score; the smallest clearance; compute per call
    as the median of its runs' medians and the largest p99."""
    out = []
    for planner in planners:
        runs = [r for r in rows if r["planner"] == planner]
        ok = [r for r in runs if r.get("success")]
        clearances = _present(runs, "min_clearance_m")
        medians = _present(runs, "compute_median_ms")
        p99s = _present(runs, "compute_p99_ms")
        ratios = _present(runs, "compute_p99_of_period")
        out.append(
            {
                "planner": planner,
                "runs": len(runs),
                "successes": len(ok),
                "success_rate": round(len(ok) / len(runs), DIGITS) if runs else None,
                "time_to_goal_s": _mean([r.get("time_to_goal_s") for r in ok]),
                "path_length_m": _mean([r.get("path_length_m") for r in ok]),
                "min_clearance_m": min(clearances) if clearances else None,
                "jerk_rms": _mean([r.get("jerk_rms") for r in runs]),
                "barn_score": _mean([r.get("barn_score") for r in runs]),
                "compute_median_ms": round(float(np.median(medians)), DIGITS) if medians else None,
                "compute_p99_ms": max(p99s) if p99s else None,
                "compute_p99_of_period": max(ratios) if ratios else None,
            }
        )
    return out


def without_compute(report: dict[str, Any]) -> dict[str, Any]:
    """The report less the figures that measure the machine (what must not change with
    the load): what two lockstep evaluations of deterministic planners share exactly."""

    def strip(row: dict[str, Any]) -> dict[str, Any]:
        return {k: v for k, v in row.items() if k not in COMPUTE_FIELDS}

    return {
        **report,
        "summary": [strip(r) for r in report["summary"]],
        "runs": [strip(r) for r in report["runs"]],
        "settings": {k: v for k, v in report["settings"].items() if k != "workers"},
    }


def format_table(summary: list[dict[str, Any]]) -> str:
    cells = [[heading for _, heading, _ in COLUMNS]]
    for row in summary:
        cells.append(
            ["-" if row.get(key) is None else fmt.format(row[key]) for key, _, fmt in COLUMNS]
        )
    widths = [max(len(line[i]) for line in cells) for i in range(len(COLUMNS))]
    lines = [
        "  ".join(
            c.ljust(w) if i == 0 else c.rjust(w)
            for i, (c, w) in enumerate(zip(line, widths, strict=True))
        )
        for line in cells
    ]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def write_json(report: dict[str, Any], path: Path) -> None:
    path.write_text(json.dumps(report, indent=1, sort_keys=False) + "\n")


def write_csv(summary: list[dict[str, Any]], path: Path) -> None:
    keys = list(summary[0]) if summary else [k for k, _, _ in COLUMNS]
    with path.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        for row in summary:
            writer.writerow({k: "" if row.get(k) is None else row[k] for k in keys})


def draw_summary(summary: list[dict[str, Any]], scenarios: int, path: Path) -> None:
    """Bars per planner: success rate, time to goal, BARN score, compute p99 per call."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = (
        ("success_rate", "success rate"),
        ("time_to_goal_s", "time to goal [s] (successes)"),
        ("path_length_m", "path length [m] (successes)"),
        ("jerk_rms", "jerk RMS [m/s³]"),
        ("barn_score", "BARN score"),
        ("compute_p99_ms", "compute p99 per call [ms]"),
    )
    names = [r["planner"] for r in summary]
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), constrained_layout=True)
    for ax, (key, title) in zip(axes.flat, panels, strict=True):
        values = [r.get(key) for r in summary]
        heights = [v if v is not None and math.isfinite(v) else 0.0 for v in values]
        ax.bar(range(len(names)), heights, color=[f"C{i}" for i in range(len(names))])
        ax.set_xticks(range(len(names)), names, rotation=20, ha="right")
        ax.set_title(title)
    fig.suptitle(f"nav2-pyif eval: {len(names)} planner(s) x {scenarios} scenario(s)")
    fig.savefig(path, dpi=100)
    plt.close(fig)
