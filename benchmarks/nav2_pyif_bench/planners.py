"""Planners for the benchmarks: as cheap as possible, so what is measured is the path."""

from __future__ import annotations

from typing import Any

from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, GoalTolerances, Plan


class TrivialController(Controller):
    """Returns a constant command; touches the plan as NumPy so set_plan's cost is real."""

    def set_plan(self, plan: Plan) -> None:
        self.plan = plan
        self.last_plan_length = plan.xy_yaw.shape[0]  # (N, 3) NumPy, computed here

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        cmd = TwistStamped(header=pose.header)
        cmd.twist.linear.x = 0.1
        return cmd


class TrivialControllerV2(TrivialController):
    """A 'new version' for hot-swap runs: reports 2.0 in angular.x."""

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        cmd = super().compute_velocity_commands(pose, velocity, goal_checker)
        cmd.twist.angular.x = 2.0
        return cmd


class InputReader(TrivialController):
    """Reads every input that arrived with the call in its NumPy form (nav2_pyif.inputs does
    the conversion when the call arrives): what a learned controller pays, and no more."""

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        for name in self.inputs.updated:
            self.inputs[name]
        return super().compute_velocity_commands(pose, velocity, goal_checker)
