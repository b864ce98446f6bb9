"""Nav2's StoppedGoalChecker and SimpleProgressChecker as nav2_pyif plugins (the rules in
``checkers``; parameter names and defaults from nav2_controller/plugins/*.cpp), served to
controller_server::

    planner-host --key nav2_pyif/robot1/goal_checker \\
        --planner nav2_pyif_planners.checker_plugins:StoppedGoalChecker
    planner-host --key nav2_pyif/robot1/progress_checker \\
        --planner nav2_pyif_planners.checker_plugins:SimpleProgressChecker
"""

from __future__ import annotations

import time
from typing import Any

from nav2_pyif import GoalChecker, GoalTolerances, ProgressChecker, pose_xy_yaw
from nav2_pyif.params import ParamValue

from nav2_pyif_planners.checkers import ProgressCheck, StoppedGoalCheck


class StoppedGoalChecker(GoalChecker):
    """Reached: within the xy and yaw tolerances (the position latched once reached while
    ``stateful``) and moving no faster than the stopped velocities."""

    def configure(self) -> None:
        p = self.params
        p.declare("xy_goal_tolerance", 0.25, "[m]")
        p.declare("yaw_goal_tolerance", 0.25, "[rad]")
        p.declare("stateful", True, "keep the position reached until reset")
        p.declare("symmetric_yaw_tolerance", False, "the goal's reverse heading counts too")
        p.declare("trans_stopped_velocity", 0.25, "[m/s]")
        p.declare("rot_stopped_velocity", 0.25, "[rad/s]")
        self.rule = StoppedGoalCheck()
        self.on_parameters_changed({})

    def on_parameters_changed(self, changed: dict[str, ParamValue]) -> None:
        p, rule = self.params, self.rule
        rule.xy_goal_tolerance = float(p["xy_goal_tolerance"])
        rule.yaw_goal_tolerance = float(p["yaw_goal_tolerance"])
        rule.stateful = bool(p["stateful"])
        rule.symmetric_yaw_tolerance = bool(p["symmetric_yaw_tolerance"])
        rule.trans_stopped_velocity = float(p["trans_stopped_velocity"])
        rule.rot_stopped_velocity = float(p["rot_stopped_velocity"])

    def is_goal_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
        v = (velocity.linear.x, velocity.linear.y, velocity.angular.z)
        return self.rule.is_goal_reached(pose_xy_yaw(pose), pose_xy_yaw(goal), v)

    def get_tolerances(self) -> GoalTolerances:
        return self.rule.tolerances()

    def reset(self) -> None:
        self.rule.reset()


class SimpleProgressChecker(ProgressChecker):
    """Progress: the robot moved more than ``required_movement_radius`` within
    ``movement_time_allowance`` seconds. Time is the pose's stamp (the ROS time of Nav2's
    pose lookup, so ``use_sim_time`` works), the host's monotonic clock when it is zero."""

    def configure(self) -> None:
        p = self.params
        p.declare("required_movement_radius", 0.5, "[m]")
        p.declare("movement_time_allowance", 10.0, "[s]")
        self._now = 0.0
        self.rule = ProgressCheck(clock=lambda: self._now)
        self.on_parameters_changed({})

    def on_parameters_changed(self, changed: dict[str, ParamValue]) -> None:
        self.rule.required_movement_radius = float(self.params["required_movement_radius"])
        self.rule.movement_time_allowance = float(self.params["movement_time_allowance"])

    def check(self, pose: Any) -> bool:
        stamp = pose.header.stamp.sec + pose.header.stamp.nanosec * 1e-9  # [s]
        self._now = stamp if stamp else time.monotonic()
        return self.rule.check(pose.pose.position.x, pose.pose.position.y)

    def reset(self) -> None:
        self.rule.reset()
