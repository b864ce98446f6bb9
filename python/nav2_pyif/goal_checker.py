"""Base class of Python goal checkers: mirrors nav2_core::GoalChecker (controller_server).
What ``get_tolerances`` returns, the tolerances a controller receives (getTolerances), is
``nav2_pyif.GoalTolerances``."""

from __future__ import annotations

import math
from abc import abstractmethod
from typing import Any, ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.plugin import PlannerPlugin


class GoalChecker(PlannerPlugin):
    """Subclass and implement ``is_goal_reached``; ``configure`` is Nav2's ``initialize``
    (goal checkers have no activate/deactivate in Nav2)."""

    plugin_type: ClassVar[PluginType] = PluginType.GOAL_CHECKER

    @abstractmethod
    def is_goal_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
        """``pose``, ``goal``: geometry_msgs/Pose in the costmap's global frame;
        ``velocity``: geometry_msgs/Twist in the robot base frame. True when reached."""

    def is_goal_xy_reached(self, pose: Any, goal: Any, velocity: Any) -> bool:
        """Nav2 Lyrical's isGoalXYReached (its controllers ask it to turn in place at the goal):
        the position only, yaw ignored. The default: within ``get_tolerances()``'s xy
        tolerance, as Nav2's SimpleGoalChecker; without tolerances, ``is_goal_reached``."""
        tolerances = self.get_tolerances()
        if tolerances is None:
            return bool(self.is_goal_reached(pose, goal, velocity))
        dx = goal.position.x - pose.position.x
        dy = goal.position.y - pose.position.y
        return math.hypot(dx, dy) <= tolerances.xy_goal_tolerance

    def get_tolerances(self) -> GoalTolerances | None:
        """The tolerances a controller sees through getTolerances; None when this checker
        has none (getTolerances returns false). ``path_length_tolerance`` reaches Nav2 on
        Lyrical (its getTolerances' third value; None: Nav2's "not measured")."""
        return None

    def reset(self) -> None:
        """Forget per-goal state (controller_server calls it for every new goal)."""
