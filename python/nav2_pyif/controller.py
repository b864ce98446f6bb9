"""Base class of Python controllers: mirrors nav2_core::Controller."""

from __future__ import annotations

from abc import abstractmethod
from typing import Any, ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif._context import PluginContext
from nav2_pyif.debug import DebugOutputs
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.inputs import Inputs
from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin


class Controller(PlannerPlugin):
    """Subclass and implement ``compute_velocity_commands``::

        from geometry_msgs.msg import TwistStamped
        from nav2_pyif import Controller

        class GoStraight(Controller):
            def configure(self) -> None:
                self.speed = self.params.declare("speed", 0.3, "forward speed [m/s]")

            def compute_velocity_commands(self, pose, velocity, goal_checker):
                cmd = TwistStamped(header=pose.header)
                cmd.twist.linear.x = self.speed
                return cmd

    Poses, the plan and the costmap share one frame (the costmap's global frame).

    Sensor topics listed in the plugin's ``inputs`` parameter arrive in ``self.inputs``
    (nav2_pyif.inputs); debug outputs declared in ``debug_outputs`` are handed to
    ``publish_debug`` during a cycle (nav2_pyif.debug).
    """

    plugin_type: ClassVar[PluginType] = PluginType.CONTROLLER
    #: Debug outputs this controller may publish: name -> ROS message type. The plugin
    #: publishes each on ``<plugin name>/<name>`` (e.g. FollowPath/trajectories).
    debug_outputs: ClassVar[dict[str, str]] = {}

    #: The latest plan (set by the default ``set_plan``), None before the first.
    plan: Plan | None = None
    #: The goal of the plan being followed (geometry_msgs/PoseStamped, the global frame), set
    #: before each ``set_plan``: Nav2's global goal on Lyrical, the plan's last pose before.
    global_goal: Any = None
    #: The latest speed limit: (value, is_percentage), None when unlimited.
    speed_limit: tuple[float, bool] | None = None

    def _attach(self, context: PluginContext) -> None:
        super()._attach(context)
        # wanted by nobody until a call says otherwise: publish_debug is a no-op offline too
        context.debug = DebugOutputs(self.debug_outputs)

    @property
    def control_period(self) -> float | None:
        """[s] the time between control cycles: 1 / the controller server's
        ``controller_frequency`` (offline: 1 / ``nav2-pyif sim --rate``), what an MPC takes as
        its time step; None when the plugin did not say (one older than this field)."""
        hz = self._context.nav2_params.get("controller_frequency")
        if isinstance(hz, int | float) and not isinstance(hz, bool) and hz > 0:
            return 1.0 / float(hz)
        return None

    @property
    def inputs(self) -> Inputs:
        """The latest message of each input topic, by its name in the ``inputs`` parameter:
        NumPy forms for scans, clouds, images, odometry and IMU, else the rclpy message."""
        return self._context.inputs

    def debug_wanted(self, name: str) -> bool:
        """Whether someone subscribes to debug output ``name`` now (skip building it if not)."""
        return name in self._context.debug.wanted

    def publish_debug(self, name: str, value: Any) -> None:
        """Return a debug output with this cycle's command: a message of the declared type or
        its array form (nav2_pyif.debug). Dropped when nobody subscribes."""
        self._context.debug.publish(name, value)

    def set_plan(self, plan: Plan) -> None:
        """The plan to follow, in the global frame: ``plan.xy_yaw`` is (N, 3) x, y [m], yaw
        [rad]; ``plan`` also reads like a nav_msgs/Path. The default stores it in
        ``self.plan``. Humble and Jazzy: Nav2's global plan, called when it changes. Lyrical:
        the part of it controller_server transformed and pruned for the cycle (its
        PathHandler), called before each cycle in which it changed."""
        self.plan = plan

    @abstractmethod
    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        """One control cycle.

        pose: geometry_msgs/PoseStamped, the robot in the global frame.
        velocity: geometry_msgs/Twist, current velocity in the robot base frame.
        goal_checker: the goal checker's tolerances, or None.
        Returns a geometry_msgs/TwistStamped (every component finite) or raises a
        nav2_core-named exception (NoValidControl, FailedToMakeProgress, ...).
        """

    def set_speed_limit(self, speed_limit: float, percentage: bool) -> None:
        """Limit speed to ``speed_limit`` m/s, or to that percentage of the maximum.
        The default stores it in ``self.speed_limit`` (0 / 100 % means no limit)."""
        unlimited = speed_limit <= 0.0 or (percentage and speed_limit >= 100.0)
        self.speed_limit = None if unlimited else (speed_limit, percentage)

    def cancel(self) -> bool:
        """Nav2 asks to stop (Jazzy+). Return True once the robot may be considered stopped."""
        return True

    def reset(self) -> None:
        """Forget per-goal state (Jazzy+)."""
