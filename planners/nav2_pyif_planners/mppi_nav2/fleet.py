"""Nav2MPPI for a fleet: the cycles of N robots in one compiled call, the step vmapped over a
robot axis (``planner-host --batch`` calls ``Nav2MPPI.compute_velocity_commands_batch``).

Robots share a call when their settings and costmap shapes match. Each keeps its own plan,
warm start, smoothing history, noise pick and costmap; the noise bank is the batch's first
robot's (every robot of one seed draws the same bank). The robot count is padded to
``nav2_pyif.batch.bucket`` sizes (few compiled shapes); the costmaps are stacked once per
change of any robot's costmap version, not per cycle."""

from __future__ import annotations

import time
from functools import partial
from typing import TYPE_CHECKING, Any, cast

import jax
import jax.numpy as jnp
import numpy as np
from nav2_pyif.batch import Batch, bucket, pad_rows

from nav2_pyif_planners.mppi_nav2.costs import Grid
from nav2_pyif_planners.mppi_nav2.optimizer import Outputs, _packed_step
from nav2_pyif_planners.mppi_nav2.params import Settings

if TYPE_CHECKING:
    from nav2_pyif_planners.mppi_nav2.controller import Nav2MPPI


@partial(jax.jit, static_argnames=("s",))
def fleet_step(
    sequence: Any, history: Any, bank: Any, packed: Any, grid: Grid, s: Settings
) -> Outputs:
    """``_packed_step`` over a leading robot axis of every argument but ``bank``."""
    one = partial(_packed_step, s=s)
    out: Outputs = jax.vmap(one, in_axes=(0, 0, None, 0, 0))(sequence, history, bank, packed, grid)
    return out


class _Stacked:
    """The stacked costmaps of the last robots served together, kept while none changed."""

    def __init__(self) -> None:
        self.grids: tuple[Grid, ...] = ()
        self.stacked: Grid | None = None

    def of(self, grids: tuple[Grid, ...]) -> Grid:
        if (
            self.stacked is None
            or len(grids) != len(self.grids)
            or any(a is not b for a, b in zip(grids, self.grids, strict=True))
        ):
            self.grids = grids
            # stacked in NumPy (one copy), put on the device once: not re-sent every cycle
            self.stacked = Grid(
                *(jnp.asarray(np.stack([np.asarray(g[k]) for g in grids])) for k in range(4))
            )
        return self.stacked


_STACKED: dict[Any, _Stacked] = {}


def shape_of(robot: Nav2MPPI) -> tuple[Any, ...]:
    """What robots must share to be served by one compiled call."""
    grid = robot._upload_costmap()
    return (robot.settings, grid.data.shape, grid.outline.shape, robot.bank.shape)


def optimise_fleet(
    robots: list[Nav2MPPI], inputs: list[np.ndarray], pad_to: int = 0
) -> list[np.ndarray | Exception]:
    """One step for each robot (of one shape) on its packed inputs, in one call. -> each
    robot's command (vx, vy, wz), or its error; warm starts kept as ``optimise`` keeps them."""
    size = max(pad_to, bucket(len(robots)))
    for robot, packed in zip(robots, inputs, strict=True):
        robot.pick_noise(packed)
    grids = tuple(robot._upload_costmap() for robot in robots)
    grids += grids[-1:] * (size - len(grids))
    key = shape_of(robots[0])
    stacked = _STACKED.setdefault(key, _Stacked()).of(grids)
    out = fleet_step(
        pad_rows(np.stack([np.asarray(r.sequence) for r in robots]), size),
        pad_rows(np.stack([np.asarray(r.history) for r in robots]), size),
        robots[0].bank,
        pad_rows(np.stack(inputs), size),
        stacked,
        robots[0].settings,
    )
    sequence, history, reply, optimal = (np.asarray(a) for a in out)
    results: list[np.ndarray | Exception] = []
    for n, robot in enumerate(robots):
        if reply[n, 3] != 0.0:  # every rollout collided: Nav2's reset and retry, alone
            robot.reset()
            try:
                results.append(robot.optimise(inputs[n], failures=1))
            except Exception as exc:  # this robot's own error
                results.append(exc)
            continue
        robot.sequence, robot.history, robot._optimal = sequence[n], history[n], optimal[n]
        results.append(robot.checked(reply[n, :3]))
    return results


def compute_batch(batch: Batch) -> list[Any]:
    """Every robot's cycle, robots of one shape in one call. A robot's own error (no plan,
    an invalid path, no valid control) is its item; the others are served."""
    out: list[Any] = [None] * len(batch)
    groups: dict[Any, list[tuple[int, Nav2MPPI, np.ndarray]]] = {}
    for i, planner in enumerate(batch.planners):
        robot = cast("Nav2MPPI", planner)  # a batch holds one planner class's robots
        try:
            packed = robot.cycle_inputs(
                batch.poses[i], batch.velocity_messages[i], batch.goal_checkers[i]
            )
            groups.setdefault(shape_of(robot), []).append((i, robot, packed))
        except Exception as exc:  # this robot's own error
            out[i] = exc
    for group in groups.values():
        started = time.perf_counter()
        commands = optimise_fleet([r for _, r, _ in group], [p for _, _, p in group])
        for (i, robot, _), command in zip(group, commands, strict=True):
            robot.last_compute_s = time.perf_counter() - started
            if isinstance(command, Exception):
                out[i] = command
                continue
            if robot.debug_wanted("local_plan"):
                robot._publish_local_plan(batch.poses[i], np.asarray(robot._optimal))
            out[i] = robot.twist(batch.pose_messages[i], command)
    return out
