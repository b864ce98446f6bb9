"""Base class of Python path handlers: mirrors Nav2 Lyrical's nav2_core::PathHandler.

On Lyrical, controller_server no longer hands the controller the whole plan: every control
cycle its path handler picks the part of the plan near the robot, and that part (transformed
into the costmap's frame) is what the controller follows. A Python path handler decides that
part; the C++ plugin does the frames.

Example::

    from nav2_pyif import PathHandler

    class Ahead(PathHandler):
        def find_plan_segment(self, pose):
            xy = self.plan.array[:, :2]
            here = int(((xy - [pose.pose.position.x, pose.pose.position.y]) ** 2).sum(1).argmin())
            return here, min(here + 40, len(self.plan))
"""

from __future__ import annotations

from abc import abstractmethod
from typing import Any, ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin


class PathHandler(PlannerPlugin):
    """Subclass and implement ``find_plan_segment``; ``configure`` is Nav2's ``initialize``
    (a path handler has no activate/deactivate in Nav2).

    Nav2's calls and what this class sees:

    ==============================  ===============================================
    nav2_core::PathHandler          Python
    ==============================  ===============================================
    ``initialize(...)``             ``configure()`` (``self.params``, the costmap)
    ``setPlan(path)``               ``set_plan(plan)``: once per new plan
    ``findPlanSegment(pose)``       ``find_plan_segment(pose)`` -> ``(start, end)``
    ``transformLocalPlan(b, e)``    none: the plugin copies ``plan[start:end]``
    ``getTransformedGoal(stamp)``   none: the plugin gives the plan's last pose
    ==============================  ===============================================
    """

    plugin_type: ClassVar[PluginType] = PluginType.PATH_HANDLER
    #: The plan ``set_plan`` last gave, in its own frame (``plan.frame_id``); empty before.
    plan: Plan = Plan([], "")

    def set_plan(self, plan: Plan) -> None:
        """A new plan (controller_server's setPlan, at every new or updated FollowPath goal),
        in its own frame (the planner's: usually ``map``), as Nav2's path handlers get it. The
        default keeps it as ``self.plan``: override to reset per-plan state, then call this."""
        self.plan = plan

    @abstractmethod
    def find_plan_segment(self, pose: Any) -> tuple[int, int]:
        """``pose``: geometry_msgs/PoseStamped, the robot in the plan's frame.

        Return ``(start, end)``: the poses ``self.plan[start:end]`` the controller follows
        this cycle (``0 <= start < end <= len(self.plan)``), indices into the plan as
        ``set_plan`` gave it. Pruning is remembering where the robot got to: Nav2's default
        never goes back before the start it returned last. Raise ``InvalidPath`` when the
        plan cannot be followed; an index out of range is an ``InvalidPath`` too."""
