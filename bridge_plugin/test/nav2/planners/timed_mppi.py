"""The MPPI side-by-side's Python controllers, each timed as Nav2's MPPI times itself: the
controller method alone, logged once per call ("compute: 7.83 ms") for the driver
(test_mppi_side_by_side.py) to read from the host's log, as it reads Nav2's "Control loop
execution time" lines from controller_server's. A batched host's call for a fleet
(``compute_velocity_commands_batch``) is logged whole, with its robot count ("batch compute:
21.40 ms, 10 robots"), for test_mppi_fleet_stacks.py; so is TimedCarrot's, the fleet's
reference for what serving costs with next to no planning in it."""

from __future__ import annotations

import logging
import math
import time
from typing import Any

import numpy as np
from nav2_pyif import GoalTolerances
from nav2_pyif.geometry import point_at_distance, wrap
from nav2_pyif_planners.follower import PathFollower
from nav2_pyif_planners.mppi import MPPI
from nav2_pyif_planners.mppi_jax import MPPIJax
from nav2_pyif_planners.mppi_nav2 import Nav2MPPI

LOG = logging.getLogger("timed_mppi")


class _Timed:
    """Times ``compute_velocity_commands`` of the controller class it is mixed into."""

    def compute_velocity_commands(self, *args: Any, **kwargs: Any) -> Any:
        started = time.perf_counter()
        try:
            return super().compute_velocity_commands(*args, **kwargs)  # type: ignore[misc]
        finally:
            LOG.info("compute: %.3f ms", (time.perf_counter() - started) * 1e3)


def _log_batch(started: float, robots: int) -> None:
    elapsed = (time.perf_counter() - started) * 1e3
    LOG.info("batch compute: %.3f ms, %d robots", elapsed, robots)


class TimedNav2MPPI(_Timed, Nav2MPPI):
    @classmethod
    def compute_velocity_commands_batch(cls, batch: Any) -> list[Any]:
        started = time.perf_counter()
        try:
            return super().compute_velocity_commands_batch(batch)
        finally:
            _log_batch(started, len(batch))


class TimedCarrot(PathFollower):
    """Turns towards a carrot 0.6 m down the plan at 0.3 m/s, a few NumPy operations a robot,
    served batched: next to no planning, so that a fleet's host CPU is what serving costs."""

    SPEED, LOOKAHEAD = 0.3, 0.6  # [m/s], [m]

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        x, y, yaw, path = self.track(pose)
        cmd = self.command(pose)
        if self.turn_at_goal(cmd, x, y, yaw, path, goal_checker):
            return cmd
        carrot = point_at_distance(path[:, :2], self.index, self.LOOKAHEAD)
        heading = float(wrap(math.atan2(carrot[1] - y, carrot[0] - x) - yaw))
        cmd.twist.linear.x = self.SPEED if abs(heading) < 0.8 else 0.0
        cmd.twist.angular.z = float(np.clip(2.0 * heading, -1.0, 1.0))
        return cmd

    @classmethod
    def compute_velocity_commands_batch(cls, batch: Any) -> list[Any]:
        started = time.perf_counter()
        out: list[Any] = []
        for i, robot in enumerate(batch.planners):
            try:
                out.append(
                    robot.compute_velocity_commands(
                        batch.pose_messages[i], batch.velocity_messages[i],
                        batch.goal_checkers[i],
                    )
                )  # fmt: skip
            except Exception as exc:  # this robot's own error
                out.append(exc)
        _log_batch(started, len(batch))
        return out


class TimedMPPIJax(_Timed, MPPIJax):
    pass


class TimedMPPI(_Timed, MPPI):
    pass
