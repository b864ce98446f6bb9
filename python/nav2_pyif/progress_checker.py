"""Base class of Python progress checkers: mirrors nav2_core::ProgressChecker."""

from __future__ import annotations

from abc import abstractmethod
from typing import Any, ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.plugin import PlannerPlugin


class ProgressChecker(PlannerPlugin):
    """Subclass and implement ``check``; ``configure`` is Nav2's ``initialize``. A progress
    checker has no costmap in Nav2: ``self.costmap`` is 0 x 0."""

    plugin_type: ClassVar[PluginType] = PluginType.PROGRESS_CHECKER

    @abstractmethod
    def check(self, pose: Any) -> bool:
        """``pose``: geometry_msgs/PoseStamped, the robot in the costmap's global frame.
        False when the robot failed to make progress: controller_server then aborts the
        FollowPath action with FailedToMakeProgress."""

    def reset(self) -> None:
        """Forget the progress baseline (controller_server calls it for every new goal)."""
