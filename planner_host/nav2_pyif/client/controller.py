"""Client of a Python controller: what nav2_pyif's C++ controller plugin does, in Python."""

from __future__ import annotations

from typing import Any

from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.messages import pose_to_wire, twist_stamped_from_wire, twist_to_list
from nav2_pyif.plan import Plan


class ControllerClient(PluginClient):
    plugin_type = PluginType.CONTROLLER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "FollowPath")
        kwargs.setdefault("node", "controller_server")
        super().__init__(*args, **kwargs)
        self._plan: dict[str, Any] | None = None
        self._speed_limit: tuple[float, bool] | None = None

    def set_plan(self, path: Plan | Any) -> None:
        """``path``: a Plan or a nav_msgs/Path, in the costmap's global frame."""
        plan = path if isinstance(path, Plan) else Plan.from_msg(path)
        self._plan = plan.to_wire()  # kept even if this call fails: re-sent on re-establishment
        self._call(Op.SET_PLAN, {"path": self._plan})

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalChecker | None = None
    ) -> Any:
        """PoseStamped + Twist -> TwistStamped (finite, or an exception)."""
        body: dict[str, Any] = {"pose": pose_to_wire(pose), "velocity": twist_to_list(velocity)}
        if goal_checker is not None:
            body["goal_checker"] = goal_checker.to_wire()
        reply = self._call(Op.COMPUTE_VELOCITY_COMMANDS, body, with_costmap=True)
        return twist_stamped_from_wire(reply["cmd_vel"])

    def set_speed_limit(self, speed_limit: float, percentage: bool) -> None:
        # kept even if this call fails (no host right now): a slow zone must survive a restart
        self._speed_limit = (speed_limit, percentage)
        self._call(Op.SET_SPEED_LIMIT, {"speed_limit": speed_limit, "percentage": percentage})

    def cancel(self) -> bool:
        cancelled: bool = self._call(Op.CANCEL, {})["cancelled"]
        return cancelled

    def reset(self) -> None:
        self._call(Op.RESET, {})

    def cleanup(self) -> None:
        self._plan, self._speed_limit = None, None
        super().cleanup()

    def _restore_state(self) -> None:
        if self._plan is not None:
            self._call(Op.SET_PLAN, {"path": self._plan}, allow_resync=False)
        if self._speed_limit is not None:
            limit, percentage = self._speed_limit
            self._call(
                Op.SET_SPEED_LIMIT,
                {"speed_limit": limit, "percentage": percentage},
                allow_resync=False,
            )
