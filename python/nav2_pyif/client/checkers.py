"""Clients of Python goal and progress checkers: what nav2_pyif's C++ checker plugins do."""

from __future__ import annotations

import math
from typing import Any

from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif._messages import pose_to_wire, twist_to_list
from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.goal_tolerances import GoalTolerances


class GoalCheckerClient(PluginClient):
    plugin_type = PluginType.GOAL_CHECKER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "goal_checker")
        kwargs.setdefault("node", "controller_server")
        super().__init__(*args, **kwargs)

    def is_goal_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
        """geometry_msgs/Pose pose and goal (the costmap's global frame), Twist velocity."""
        body = {
            "pose": pose7(pose),
            "goal": pose7(goal),
            "velocity": twist_to_list(velocity),
        }
        reached: bool = self._call(Op.IS_GOAL_REACHED, body)["reached"]
        return reached

    def is_goal_xy_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
        """Lyrical's isGoalXYReached: is_goal_reached with xy_only."""
        body = {
            "pose": pose7(pose),
            "goal": pose7(goal),
            "velocity": twist_to_list(velocity),
            "xy_only": True,
        }
        reached: bool = self._call(Op.IS_GOAL_REACHED, body)["reached"]
        return reached

    def get_tolerances(self) -> GoalTolerances | None:
        return tolerances_from_wire(self._call(Op.GET_TOLERANCES, {}))

    def reset(self) -> None:
        self._call(Op.RESET, {})


class ProgressCheckerClient(PluginClient):
    plugin_type = PluginType.PROGRESS_CHECKER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "progress_checker")
        kwargs.setdefault("node", "controller_server")
        super().__init__(*args, **kwargs)

    def check(self, pose: Any) -> bool:
        """geometry_msgs/PoseStamped -> False when the robot failed to make progress."""
        progress: bool = self._call(Op.CHECK, {"pose": pose_to_wire(pose)})["making_progress"]
        return progress

    def reset(self) -> None:
        self._call(Op.RESET, {})


def pose7(pose: Any) -> list[float]:
    """geometry_msgs/Pose -> x, y, z, qx, qy, qz, qw."""
    p, q = pose.position, pose.orientation
    return [p.x, p.y, p.z, q.x, q.y, q.z, q.w]


def tolerances_from_wire(body: dict[str, Any]) -> GoalTolerances | None:
    """A get_tolerances reply's tolerances (the inverse of the host's tolerances_to_wire)."""
    if not body["available"]:
        return None
    pose, velocity = body["pose_tolerance"], body["velocity_tolerance"]
    yaw = 2.0 * math.atan2(pose[5], pose[6])
    return GoalTolerances(pose[0], yaw, velocity[0], velocity[5], body.get("path_length_tolerance"))
