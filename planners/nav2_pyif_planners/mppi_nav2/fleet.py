"""Nav2MPPI for a fleet: the cycles of N robots in one host call (``planner-host --batch``
calls ``Nav2MPPI.compute_velocity_commands_batch``).

Each robot's own compiled step, dispatched as soon as its inputs are packed and before any
result is read, not one step vmapped over a robot axis: on a CPU the vmapped step cost twice
the single one per robot (its gathers from per-robot costmaps and plans become batched
gathers), while N dispatched steps run on XLA's threads at the single step's cost, and the
first robots' steps run while Python packs the next robots' inputs (BENCHMARKS.md). The
robots sit on JAX's devices in turn, one per CPU core (lanes.py), so their steps run side by
side. Each robot keeps its own plan, warm start, smoothing history, noise pick and costmap;
nothing is padded or stacked, and no fleet size is compiled apart."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from nav2_pyif.batch import Batch

if TYPE_CHECKING:
    from nav2_pyif_planners.mppi_nav2.controller import Nav2MPPI
    from nav2_pyif_planners.mppi_nav2.optimizer import Outputs


def compute_batch(batch: Batch) -> list[Any]:
    """Every robot's cycle. A robot's own error (no plan, an invalid path, no valid control)
    is its item; the others are served."""
    out: list[Any] = [None] * len(batch)
    started = time.perf_counter()
    launched: list[tuple[int, Nav2MPPI, np.ndarray, Outputs]] = []
    for i, planner in enumerate(batch.planners):
        robot = cast("Nav2MPPI", planner)  # a batch holds one planner class's robots
        try:
            packed = robot.cycle_inputs(
                batch.poses[i], batch.velocity_messages[i], batch.goal_checkers[i]
            )
            launched.append((i, robot, packed, robot._run(packed)))
        except Exception as exc:  # this robot's own error
            out[i] = exc
    for i, robot, packed, step in launched:
        try:
            command = robot.optimise(packed, step)
        except Exception as exc:  # this robot's own error
            out[i] = exc
            continue
        robot.last_compute_s = time.perf_counter() - started
        if robot.debug_wanted("local_plan"):
            robot._publish_local_plan(batch.poses[i], np.asarray(robot._optimal))
        out[i] = robot.twist(batch.pose_messages[i], command)
    return out
