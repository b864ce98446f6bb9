"""A replay's summary: a table per key and op, a JSON file, a PNG of the differences over
time."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from nav2_pyif.replay.compare import CallDiff
from nav2_pyif.replay.engine import ReplayResult


def _largest(values: list[float | None]) -> float | None:
    present = [abs(v) for v in values if v is not None]
    return max(present) if present else None


def _percentiles(values: list[float | None]) -> dict[str, float] | None:
    present = [v for v in values if v is not None]
    if not present:
        return None
    return {"median": float(np.median(present)), "p99": float(np.percentile(present, 99))}


def group_summary(calls: list[CallDiff]) -> dict[str, Any]:
    return {
        "calls": len(calls),
        "identical": sum(c.identical for c in calls),
        "errors": sum(bool(c.error) for c in calls),
        "recorded_errors": sum(bool(c.recorded_error) for c in calls),
        "max_abs_dv": _largest([c.dv for c in calls]),
        "max_abs_dw": _largest([c.dw for c in calls]),
        "plan_max": _largest([c.plan_max for c in calls]),
        "plan_mean": _largest([c.plan_mean for c in calls]),
        "compute_ms": _percentiles([c.compute_ms for c in calls]),
        "recorded_compute_ms": _percentiles([c.recorded_compute_ms for c in calls]),
    }


def summary(result: ReplayResult) -> dict[str, Any]:
    groups: dict[str, dict[str, list[CallDiff]]] = {}
    for call in result.calls:
        groups.setdefault(call.key, {}).setdefault(call.op, []).append(call)
    return {
        "files": [str(p) for p in result.files],
        "planners": result.planners,
        "recorded_planners": result.recorded,
        "calls": len(result.calls),
        "identical": sum(c.identical for c in result.calls),
        "errors": sum(bool(c.error) for c in result.calls),
        "restored": result.restored,
        "reloads": [{"t": t, "key": key, "planner": label} for t, key, label in result.reloads],
        "wall_s": result.wall_s,
        "by_key": {
            key: {op: group_summary(calls) for op, calls in ops.items()}
            for key, ops in groups.items()
        },
    }


def write_json(result: ReplayResult, path: Path) -> None:
    record = {"summary": summary(result), "calls": [c.to_json() for c in result.calls]}
    path.write_text(json.dumps(record, indent=1) + "\n")


def _ms(stats: dict[str, float] | None) -> str:
    return f"{stats['median']:.2f} / {stats['p99']:.2f}" if stats else "-"


def _m(value: float | None, digits: int = 3) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def table(result: ReplayResult) -> str:
    """The per key and op figures, side by side."""
    info = summary(result)
    header = (
        f"  {'op':<28} {'calls':>6} {'same':>6} {'errors':>6} {'|dv| max':>9} "
        f"{'|dw| max':>9} {'plan max m':>10} {'compute ms med/p99':>19} {'recorded ms':>15}"
    )
    lines = []
    for key, ops in info["by_key"].items():
        lines.append(f"{key}: {result.planners[key]} (recorded: {result.recorded[key]})")
        lines.append(header)
        for op, s in ops.items():
            lines.append(
                f"  {op:<28} {s['calls']:>6} {s['identical']:>6} {s['errors']:>6} "
                f"{_m(s['max_abs_dv']):>9} {_m(s['max_abs_dw']):>9} {_m(s['plan_max']):>10} "
                f"{_ms(s['compute_ms']):>19} {_ms(s['recorded_compute_ms']):>15}"
            )
    lines += [
        f"hot swap at {t:.2f} s on {key} (recorded: {label}): the replayed planner reloaded"
        for t, key, label in result.reloads
    ]
    lines.append(
        f"{info['calls']} call(s) replayed in {info['wall_s']:.2f} s: {info['identical']} "
        f"identical to the recording, {info['errors']} error(s)"
        + (f"; {info['restored']} restore request(s) first" if info["restored"] else "")
    )
    return "\n".join(lines)


def plot(result: ReplayResult, path: Path) -> None:
    """Per key: the output differences (dv, dw or plan distances) and the compute time,
    recorded and replayed, over the recording's time."""
    import matplotlib

    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.pyplot as plt

    keys = list(dict.fromkeys(c.key for c in result.calls)) or ["(no calls)"]
    fig, axes = plt.subplots(len(keys), 2, figsize=(12, 3.2 * len(keys)), squeeze=False)
    for row, key in zip(axes, keys, strict=True):
        calls = [c for c in result.calls if c.key == key]
        differ, compute = row
        for label, values in (
            ("dv [m/s]", [c.dv for c in calls]),
            ("dw [rad/s]", [c.dw for c in calls]),
            ("plan max [m]", [c.plan_max for c in calls]),
            ("plan mean [m]", [c.plan_mean for c in calls]),
        ):
            points = [(c.t, v) for c, v in zip(calls, values, strict=True) if v is not None]
            if points:
                differ.plot(*zip(*points, strict=True), ".-", label=label, markersize=3)
        errors = [c.t for c in calls if c.error]
        if errors:
            differ.plot(errors, [0.0] * len(errors), "rx", label="error")
        differ.set_title(f"{key}: replayed - recorded")
        differ.set_xlabel("recording time [s]")
        for label, values in (
            ("recorded", [c.recorded_compute_ms for c in calls]),
            ("replayed", [c.compute_ms for c in calls]),
        ):
            points = [(c.t, v) for c, v in zip(calls, values, strict=True) if v is not None]
            if points:
                compute.plot(*zip(*points, strict=True), ".", label=label, markersize=3)
        compute.set_yscale("log")  # a configure's second beside cycles of a millisecond
        compute.set_title(f"{key}: planner compute per call [ms]")
        compute.set_xlabel("recording time [s]")
        for axis in row:
            if axis.lines:
                axis.legend(loc="upper right", fontsize=8)
            axis.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
