"""Nav2's goal and progress checking rules, in Python: StoppedGoalChecker (SimpleGoalChecker's
tolerances, stateful, plus "stopped" velocity limits) and SimpleProgressChecker (the robot
must move `required_movement_radius` within `movement_time_allowance`), from nav2_controller's
plugins/*.cpp, with their parameter names and defaults."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from nav2_pyif import GoalTolerances


def _angle_between(a: float, b: float) -> float:
    return abs(math.atan2(math.sin(b - a), math.cos(b - a)))


@dataclass
class StoppedGoalCheck:
    """Reached: within `xy_goal_tolerance` of the goal (latched once reached when
    `stateful`), within `yaw_goal_tolerance` of its heading (or of its reverse with
    `symmetric_yaw_tolerance`), and moving no faster than the stopped velocities."""

    xy_goal_tolerance: float = 0.25  # [m]
    yaw_goal_tolerance: float = 0.25  # [rad]
    stateful: bool = True
    symmetric_yaw_tolerance: bool = False
    trans_stopped_velocity: float = 0.25  # [m/s]
    rot_stopped_velocity: float = 0.25  # [rad/s]
    _check_xy: bool = field(default=True, repr=False)

    def reset(self) -> None:
        self._check_xy = True

    def is_goal_reached(
        self,
        pose: tuple[float, float, float],
        goal: tuple[float, float, float],
        velocity: tuple[float, float, float],
    ) -> bool:
        """``pose`` and ``goal``: (x, y, yaw); ``velocity``: (vx, vy, wz)."""
        (x, y, yaw), (gx, gy, gyaw), (vx, vy, wz) = pose, goal, velocity
        if self._check_xy:
            if math.hypot(x - gx, y - gy) > self.xy_goal_tolerance:
                return False
            if self.stateful:
                self._check_xy = False
        headings = (gyaw, gyaw + math.pi) if self.symmetric_yaw_tolerance else (gyaw,)
        if min(_angle_between(yaw, h) for h in headings) > self.yaw_goal_tolerance:
            return False
        return abs(wz) <= self.rot_stopped_velocity and (
            math.hypot(vx, vy) <= self.trans_stopped_velocity
        )

    def tolerances(self) -> GoalTolerances:
        """What getTolerances reports (the controller's view of this checker)."""
        return GoalTolerances(
            self.xy_goal_tolerance,
            self.yaw_goal_tolerance,
            self.trans_stopped_velocity,
            self.rot_stopped_velocity,
        )


@dataclass
class ProgressCheck:
    """Progress: the robot moved more than `required_movement_radius` from where it was
    `movement_time_allowance` seconds ago at most. `clock` gives seconds (monotonic)."""

    required_movement_radius: float = 0.5  # [m]
    movement_time_allowance: float = 10.0  # [s]
    clock: Callable[[], float] = field(default=time.monotonic, repr=False)
    _baseline: tuple[float, float, float] | None = field(default=None, repr=False)

    def reset(self) -> None:
        self._baseline = None

    def check(self, x: float, y: float) -> bool:
        now = self.clock()
        if self._baseline is None or (
            math.hypot(x - self._baseline[0], y - self._baseline[1]) > self.required_movement_radius
        ):
            self._baseline = (x, y, now)
            return True
        return now - self._baseline[2] <= self.movement_time_allowance
