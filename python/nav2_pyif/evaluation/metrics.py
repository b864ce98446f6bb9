"""What ``nav2-pyif eval`` measures of one run (a planner on a scenario).

Two groups: the run's figures, from simulated time and the driven trajectory, which depend
only on the planner's answers (identical on an idle and a loaded machine in lockstep); and
the compute figures (``COMPUTE_FIELDS``: the host's time per call, the wall time), which are
the machine's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from nav2_pyif.runner.run import SimResult

#: The fields that measure the machine rather than the planner's answers.
COMPUTE_FIELDS = ("compute_median_ms", "compute_p99_ms", "compute_p99_of_period", "wall_time_s")
#: BARN's robot (a Jackal) at full speed: its optimal time is the optimal path at this speed.
BARN_MAX_SPEED = 2.0
CONTROL_OP = "compute_velocity_commands"
DIGITS = 4  # figures rounded so that a report compares as text


def _rounded(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else round(value, DIGITS)


def jerk_rms(trajectory: Sequence[tuple[float, ...]], dt: float, column: int) -> float | None:
    """RMS of the second derivative of a velocity column (4: linear, 5: angular) over the
    run: its jerk [m/s^3 or rad/s^3]; None for fewer than 3 cycles."""
    if len(trajectory) < 3:
        return None
    speed = np.array([row[column] for row in trajectory])
    jerk = np.diff(speed, n=2) / dt**2
    return float(np.sqrt(np.mean(jerk**2)))


def barn_score(
    success: bool, time_s: float, optimal_length: float | None, max_speed: float
) -> float | None:
    """BARN's score: 1_success * OT / clip(AT, 4 OT, 8 OT), with OT the optimal path at the
    robot's full speed and AT the time taken; None where no optimal path is known."""
    if optimal_length is None or optimal_length <= 0:
        return None
    if not success:
        return 0.0
    optimal_time = optimal_length / max_speed
    return optimal_time / float(np.clip(time_s, 4 * optimal_time, 8 * optimal_time))


def run_metrics(
    result: SimResult, optimal_length: float | None, max_speed: float = BARN_MAX_SPEED
) -> dict[str, Any]:
    """The run's row of the report."""
    success = result.reached and result.collisions == 0
    dt = 1.0 / result.config.rate
    compute = np.array(
        [r.compute_ns for r in result.records if r.op == CONTROL_OP and r.ok], np.float64
    )
    median = float(np.median(compute)) / 1e6 if compute.size else None
    p99 = float(np.percentile(compute, 99)) / 1e6 if compute.size else None
    return {
        "success": success,
        "outcome": result.outcome,
        "time_to_goal_s": _rounded(result.sim_time) if success else None,
        "sim_time_s": _rounded(result.sim_time),
        "path_length_m": _rounded(result.driven_distance),
        "min_clearance_m": _rounded(result.min_clearance),
        "jerk_rms": _rounded(jerk_rms(result.trajectory, dt, 4)),
        "angular_jerk_rms": _rounded(jerk_rms(result.trajectory, dt, 5)),
        "collisions": result.collisions,
        "controller_errors": len(result.controller_errors),
        "cycles": result.cycles,
        "barn_score": _rounded(barn_score(success, result.sim_time, optimal_length, max_speed)),
        "compute_median_ms": _rounded(median),
        "compute_p99_ms": _rounded(p99),
        "compute_p99_of_period": _rounded(p99 / 1000.0 / dt) if p99 is not None else None,
        "wall_time_s": _rounded(result.wall_time),
    }
