"""Base class of Python global planners: mirrors nav2_core::GlobalPlanner."""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Callable, Sequence
from typing import Any, ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.plugin import PlannerPlugin


class GlobalPlanner(PlannerPlugin):
    """Subclass and implement ``create_plan``; use ``self.costmap`` for the map."""

    plugin_type: ClassVar[PluginType] = PluginType.GLOBAL_PLANNER

    #: The poses to pass through, in order, for the current ``create_plan``
    #: (geometry_msgs/PoseStamped, the global frame): Nav2 Lyrical's viapoints; empty when
    #: there are none, and on Humble and Jazzy. A planner that needs some and has none raises
    #: NoViapointsGiven.
    viapoints: Sequence[Any] = ()

    @abstractmethod
    def create_plan(self, start: Any, goal: Any, cancel_checker: Callable[[], bool]) -> Any:
        """Plan from ``start`` to ``goal`` (geometry_msgs/PoseStamped, global frame).

        Long searches should call ``cancel_checker()`` now and then and raise
        PlannerCancelled when it returns True.
        Returns a nav_msgs/Path, a ``Plan``, or a NumPy array of (N, 2) x, y / (N, 3) x, y,
        yaw / (N, 7) poses in the global frame; every value finite. Raise StartOccupied,
        GoalOccupied, NoValidPathCouldBeFound, ... when there is no plan.
        """
