"""Base class of Python path smoothers: mirrors nav2_core::Smoother (smoother_server)."""

from __future__ import annotations

from abc import abstractmethod
from typing import Any, ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin


class Smoother(PlannerPlugin):
    """Subclass and implement ``smooth``::

        from nav2_pyif import Plan, Smoother

        class Average(Smoother):
            def smooth(self, path, max_time):
                xy = path.xy.copy()
                xy[1:-1] = (xy[:-2] + xy[1:-1] + xy[2:]) / 3.0
                return Plan(xy, path.frame_id, path.stamp_ns)

    ``self.costmap`` is smoother_server's costmap (its ``costmap_topic``) once Nav2 has
    received one, else 0 x 0.
    """

    plugin_type: ClassVar[PluginType] = PluginType.SMOOTHER

    @abstractmethod
    def smooth(self, path: Plan, max_time: float) -> Any:
        """Smooth ``path`` (a Plan in its own frame: Nav2 does not transform it) within
        ``max_time`` seconds.

        Returns the smoothed path (a Plan, nav_msgs/Path or an (N, 2/3/7) array; every value
        finite), or ``(path, was_completed)`` to report, as nav2_core's ``smooth`` returns
        false, that it stopped early. Raise SmootherTimedOut, SmoothedPathInCollision,
        FailedToSmoothPath, InvalidPath, ... when there is no smoothed path.
        """
