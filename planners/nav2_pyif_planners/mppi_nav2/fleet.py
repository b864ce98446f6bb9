"""Nav2MPPI for a fleet: the cycles of N robots in one host call (``planner-host --batch``
calls ``Nav2MPPI.compute_velocity_commands_batch``).

Each robot's own compiled step, all dispatched before any result is read, not one step
vmapped over a robot axis: on a CPU the vmapped step cost twice the single one per robot
(its gathers from per-robot costmaps and plans become batched gathers), while N dispatched
steps run back to back on XLA's threads at the single step's cost (BENCHMARKS.md). Each
robot keeps its own plan, warm start, smoothing history, noise pick and costmap; nothing is
padded or stacked, and no fleet size is compiled apart."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from nav2_pyif.batch import Batch

if TYPE_CHECKING:
    from nav2_pyif_planners.mppi_nav2.controller import Nav2MPPI


def optimise_fleet(
    robots: list[Nav2MPPI], inputs: list[np.ndarray]
) -> list[np.ndarray | Exception]:
    """One step for each robot on its packed inputs. -> each robot's command (vx, vy, wz), or
    its error; warm starts kept as ``optimise`` keeps them. Every robot's step is dispatched
    before any result is read: JAX runs them while Python prepares the next, and XLA spreads
    them over the cores."""
    launched = [robot._run(packed) for robot, packed in zip(robots, inputs, strict=True)]
    results: list[np.ndarray | Exception] = []
    for robot, packed, out in zip(robots, inputs, launched, strict=True):
        reply = np.asarray(out.reply, np.float64)
        if reply[3] != 0.0:  # every rollout collided: Nav2's reset and retry, alone
            robot.reset()
            try:
                results.append(robot.optimise(packed, failures=1))
            except Exception as exc:  # this robot's own error
                results.append(exc)
            continue
        robot.sequence, robot.history, robot._optimal = out.sequence, out.history, out.optimal
        results.append(robot.checked(reply[:3]))
    return results


def compute_batch(batch: Batch) -> list[Any]:
    """Every robot's cycle. A robot's own error (no plan, an invalid path, no valid control)
    is its item; the others are served."""
    out: list[Any] = [None] * len(batch)
    ready: list[tuple[int, Nav2MPPI, np.ndarray]] = []
    for i, planner in enumerate(batch.planners):
        robot = cast("Nav2MPPI", planner)  # a batch holds one planner class's robots
        try:
            packed = robot.cycle_inputs(
                batch.poses[i], batch.velocity_messages[i], batch.goal_checkers[i]
            )
            ready.append((i, robot, packed))
        except Exception as exc:  # this robot's own error
            out[i] = exc
    started = time.perf_counter()
    commands = optimise_fleet([r for _, r, _ in ready], [p for _, _, p in ready])
    for (i, robot, _), command in zip(ready, commands, strict=True):
        robot.last_compute_s = time.perf_counter() - started
        if isinstance(command, Exception):
            out[i] = command
            continue
        if robot.debug_wanted("local_plan"):
            robot._publish_local_plan(batch.poses[i], np.asarray(robot._optimal))
        out[i] = robot.twist(batch.pose_messages[i], command)
    return out
