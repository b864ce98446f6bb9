"""What a run prints and records: a summary, a latency table per call, a JSON record."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from nav2_pyif.client.calls import CallRecord
from nav2_pyif.geometry import path_length
from nav2_pyif.runner.robot import CLEARANCE_REACH
from nav2_pyif.runner.run import CONTROLLER_FAILED, SimResult

#: Ops every plugin makes: their rows are per plugin ("configure (planner)").
SHARED_OPS = frozenset({"configure", "activate", "deactivate", "cleanup", "set_parameters"})


def _label(r: CallRecord) -> str:
    """The latency table's row of a call: its op, per plugin for the ops every plugin makes,
    apart when it carried the costmap or failed."""
    label = f"{r.op} ({r.plugin})" if r.op in SHARED_OPS and r.plugin else r.op
    if r.costmap_sent and r.op == "compute_velocity_commands":
        label += " +costmap"
    return label if r.ok else f"{label} FAILED"


def latency_rows(result: SimResult) -> list[dict[str, Any]]:
    """Per row (``_label``): calls, round trip / host compute / transport (= round trip -
    compute), in µs; failed calls (an error reply, or none in time) have rows of their own."""
    rows = []
    groups: dict[str, list[CallRecord]] = {}
    for r in result.records:
        groups.setdefault(_label(r), []).append(r)
    for label, records in groups.items():
        total = np.array([r.total_ns for r in records]) / 1000.0
        compute = np.array([r.compute_ns for r in records]) / 1000.0
        transport = np.array([r.transport_ns for r in records]) / 1000.0
        rows.append(
            {
                "op": label,
                "calls": len(records),
                "round_trip_median_us": float(np.median(total)),
                "round_trip_p99_us": float(np.percentile(total, 99)),
                "compute_median_us": float(np.median(compute)),
                "compute_p99_us": float(np.percentile(compute, 99)),
                "transport_median_us": float(np.median(transport)),
                "transport_p99_us": float(np.percentile(transport, 99)),
            }
        )
    return rows


def summary(result: SimResult) -> dict[str, Any]:
    c = result.config
    return {
        "map": str(c.map),
        "controller": result.name_of("controller"),
        "planner": result.name_of("planner"),
        "served": result.served,
        "hot_swaps": [
            {"t_s": round(s.sim_time, 3), "role": s.role, "planner": s.planner}
            for s in result.swaps
        ],
        "start": list(result.start),
        "goal": list(result.goal),
        "reached": result.reached,
        "outcome": result.outcome,
        "interrupted": result.interrupted,
        "sim_time_s": round(result.sim_time, 3),
        "wall_time_s": round(result.wall_time, 3),
        "cycles": result.cycles,
        "control_rate_hz": c.rate,
        "params_file": str(c.params_file) if c.params_file else None,
        "timing": result.timing.as_dict(),
        "plan_length_m": round(result.path_length, 3),
        "plans": c.plans,
        "failed_plans": result.failed_plans,
        "driven_distance_m": round(result.driven_distance, 3),
        # None: no step driven, nothing measured (JSON has no infinity)
        "min_clearance_m": (
            round(result.min_clearance, 3) if math.isfinite(result.min_clearance) else None
        ),
        "collisions": result.collisions,
        "controller_errors": len(result.controller_errors),
        "plugins": {role: result.name_of(role) for role in c.plugins},
        "carried_calls": list(result.carried),
        "layer_cells": int(result.layer.cells.sum()) if result.layer is not None else 0,
        "raw_plan_length_m": round(path_length(result.raw_plan), 3),
        "scans": result.scans,
        "debug_outputs": _debug_counts(result),
        "recoveries": [
            {"t_s": round(r.sim_time, 3), "seconds": round(r.seconds, 3), "outcome": r.outcome}
            for r in result.recoveries
        ],
    }


def _debug_counts(result: SimResult) -> dict[str, int]:
    """Debug output name -> how many cycles returned it."""
    counts: dict[str, int] = {}
    for _, name, _ in result.debug:
        counts[name] = counts.get(name, 0) + 1
    return counts


def _sensing_line(result: SimResult, s: dict[str, Any]) -> list[str]:
    """The simulated laser fed to the controller, and the debug outputs kept."""
    lines = []
    laser = result.config.sensing.scan
    if laser is not None:
        lines.append(
            f"  simulated scans: {laser.beams} beams, {laser.range_max:g} m, noise "
            f"{laser.noise:g} m, {s['scans']} sent as input 'scan' at "
            f"{result.config.sensing.scan_rate:g} Hz"
        )
    if s["debug_outputs"]:
        kept = ", ".join(f"{name} x{n}" for name, n in s["debug_outputs"].items())
        lines.append(f"  debug outputs drawn: {kept}")
    return lines


def _plugins_line(s: dict[str, Any]) -> list[str]:
    """Nav2's other plugins of the run, and how many cycles the goal check carried."""
    if not s["plugins"]:
        return []
    named = ", ".join(f"{role.replace('_', ' ')} {name}" for role, name in s["plugins"].items())
    carried, alone = s["carried_calls"]
    if carried or alone:
        named += (
            f"; {carried} checker/controller calls answered inside the goal check's query, "
            f"{alone} sent on their own"
        )
    return [f"  {named}"]


def _served(result: SimResult, role: str) -> str:
    """The planner of ``role``; after hot swaps, each with the simulated time it served."""
    spans = result.served_over_time(role)
    if len(spans) == 1:
        return spans[0][2]
    return ", then ".join(f"{name} ({t0:.1f}-{t1:.1f} s)" for t0, t1, name in spans) + (
        " (hot swap)" if len(spans) == 2 else " (hot swaps)"
    )


def clearance_text(metres: float | None, digits: int = 3) -> str:
    """The minimum clearance as measured: the check looks CLEARANCE_REACH far, and a run that
    drove no step measured nothing."""
    if metres is None:
        return "not measured (no step driven)"
    if metres >= CLEARANCE_REACH:
        return f"over {CLEARANCE_REACH:g} m (no obstacle nearer)"
    return f"{metres:.{digits}f} m"


def _errors_text(s: dict[str, Any]) -> str:
    """The controller's errors; the one that ended the run came in a cycle not driven (the
    cycles counted are the steps driven)."""
    errors = s["controller_errors"]
    if not s["outcome"].startswith(CONTROLLER_FAILED) or not errors:
        return str(errors)
    return f"{errors} ({errors - 1} in the {s['cycles']} cycles driven, 1 that ended the run)"


def _recoveries_line(result: SimResult, s: dict[str, Any]) -> list[str]:
    """The recovery behaviour's runs, when the run had one."""
    if not s["recoveries"]:
        return []
    runs = ", ".join(
        f"t={r['t_s']:.1f} s {r['outcome']} in {r['seconds']:.1f} s" for r in s["recoveries"]
    )
    return [f"  recoveries by {result.name_of('recovery')}: {len(s['recoveries'])} ({runs})"]


def _plans_line(s: dict[str, Any]) -> list[str]:
    """With --plans N: how many create_plan calls were timed (rows create_plan and, for
    those that raised, create_plan FAILED)."""
    if s["plans"] <= 1:
        return []
    return [
        f"  create_plan timed {s['plans']} times ({s['failed_plans']} failed); the first "
        "plan was driven"
    ]


def format_report(result: SimResult) -> str:
    s = summary(result)
    # The planner's own traceback first (the error that ended the run), then what happened.
    lines = [result.traceback.rstrip(), ""] if result.traceback else []
    lines += [
        f"{'REACHED' if s['reached'] else 'NOT REACHED'}: {s['outcome']}",
        f"  map {s['map']}, controller {_served(result, 'controller')}, planner "
        f"{_served(result, 'planner')}",
        f"  simulated time {s['sim_time_s']:.1f} s in {s['cycles']} cycles at "
        f"{s['control_rate_hz']:.0f} Hz (wall {s['wall_time_s']:.1f} s)",
        f"  plan {s['plan_length_m']:.2f} m, driven {s['driven_distance_m']:.2f} m, "
        f"minimum clearance {clearance_text(s['min_clearance_m'])}, "
        f"collisions {s['collisions']}, controller errors {_errors_text(s)}",
        result.timing.line(),
        *([f"  Nav2 params file: {s['params_file']}"] if s["params_file"] else []),
        *_plugins_line(s),
        *_sensing_line(result, s),
        *_recoveries_line(result, s),
        *_plans_line(s),
        "",
    ]
    rows = latency_rows(result)
    width = max([36, *(len(r["op"]) + 1 for r in rows)])
    lines += [
        f"{'latency per call (µs)':<{width + 3}}calls   round trip         host compute       "
        "transport",
        f"{'':<{width + 12}}median     p99     median     p99     median     p99",
    ]
    for r in rows:
        lines.append(
            f"  {r['op']:<{width}}{r['calls']:>6} {r['round_trip_median_us']:>8.0f} "
            f"{r['round_trip_p99_us']:>7.0f}   {r['compute_median_us']:>8.0f} "
            f"{r['compute_p99_us']:>7.0f}   {r['transport_median_us']:>8.0f} "
            f"{r['transport_p99_us']:>7.0f}"
        )
    if result.controller_errors:
        lines += ["", "controller errors (first 5):"]
        lines += [f"  {e}" for e in result.controller_errors[:5]]
    return "\n".join(lines)


def write_json(result: SimResult, path: Path) -> None:
    record = {
        "summary": summary(result),
        "latency": latency_rows(result),
        "plan": result.plan.round(4).tolist(),
        "trajectory": [[round(v, 4) for v in p] for p in result.trajectory],
        "trajectory_columns": ["t", "x", "y", "yaw", "v", "w"],
        "controller_errors": result.controller_errors,
        "traceback": result.traceback,
    }
    path.write_text(json.dumps(record, indent=1))
