"""The runner's own goal check, made as Nav2's controller_server makes it with SimpleGoalChecker:
on the plan's last pose (controller_server checks ``end_pose_``, the plan's back(), never the
goal asked for), within ``xy_goal_tolerance`` and then ``yaw_goal_tolerance``, the position
latched once reached when ``stateful``. And, for a run that ended otherwise, why it did not
pass."""

from __future__ import annotations

import math
from dataclasses import dataclass

from nav2_pyif.goal_tolerances import GoalTolerances

Pose3 = tuple[float, float, float]
#: [m] a plan ending farther than this from the goal asked for is said so in the report.
NOTABLE_GAP = 0.01


def _yaw_error(a: float, b: float) -> float:
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


@dataclass
class GoalCheck:
    tolerances: GoalTolerances
    goal: Pose3  # the plan's last pose
    stateful: bool = True
    xy_reached: bool = False

    def reached(self, x: float, y: float, yaw: float) -> bool:
        if not self.xy_reached:
            if math.hypot(self.goal[0] - x, self.goal[1] - y) > self.tolerances.xy_goal_tolerance:
                return False
            self.xy_reached = self.stateful
        return _yaw_error(self.goal[2], yaw) <= self.tolerances.yaw_goal_tolerance

    def passed(self) -> str:
        """How the check passed, for the outcome."""
        t = self.tolerances
        return (
            f"within xy_goal_tolerance {t.xy_goal_tolerance:g} m and yaw_goal_tolerance "
            f"{t.yaw_goal_tolerance:g} rad of the plan's last pose"
        )

    def why_not(self, x: float, y: float, yaw: float, asked: Pose3) -> str:
        """Why the check has not passed with the robot at (x, y, yaw): which tolerance it is
        outside, and where the plan ends against the goal asked for."""
        t = self.tolerances
        distance = math.hypot(self.goal[0] - x, self.goal[1] - y)
        if not self.xy_reached and distance > t.xy_goal_tolerance:
            why = (
                f"the robot is {distance:.2f} m from the plan's last pose "
                f"(xy_goal_tolerance {t.xy_goal_tolerance:g} m)"
            )
        else:
            why = (
                f"the robot is within xy_goal_tolerance of the plan's last pose but "
                f"{_yaw_error(self.goal[2], yaw):.2f} rad off its heading (yaw_goal_tolerance "
                f"{t.yaw_goal_tolerance:g} rad)"
            )
        gap = math.hypot(self.goal[0] - asked[0], self.goal[1] - asked[1])
        if gap > NOTABLE_GAP:
            why += f"; the plan ends {gap:.2f} m from the goal asked for"
        return why
