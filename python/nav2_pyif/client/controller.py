"""Client of a Python controller: what nav2_pyif's C++ controller plugin does, in Python."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif._messages import pose_to_wire, twist_stamped_from_wire, twist_to_list
from nav2_pyif._ros_types import type_name_of
from nav2_pyif.client.plugin_client import Carried, PluginClient, log
from nav2_pyif.client.ros_messages import from_cdr, to_cdr
from nav2_pyif.exceptions import Nav2Error
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.plan import Plan


class ControllerClient(PluginClient):
    plugin_type = PluginType.CONTROLLER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "FollowPath")
        kwargs.setdefault("node", "controller_server")
        super().__init__(*args, **kwargs)
        self._plan: dict[str, Any] | None = None
        # The plan's set_plan failed on the host (not on its planner): sent before the next
        # cycle, or with the state a re-established session gets.
        self._plan_owed = False
        # Lyrical (follow): the global goal, and which of plan and goal the host lacks
        self._goal: dict[str, Any] | None = None
        self._unsent: set[str] = set()
        self._follows = False  # follow() called: no command is prepared for another query
        self._speed_limit: tuple[float, bool] | None = None
        #: the debug outputs the last cycle returned, name -> rclpy message
        self.debug: dict[str, Any] = {}

    def set_plan(self, path: Plan | Any) -> Nav2Error | None:
        """``path``: a Plan or a nav_msgs/Path, in the costmap's global frame.

        Returns None when the host has it. When the host failed the call (none alive, no
        reply in time, Unavailable) the plan is kept as owed and that failure is returned, not
        raised: the next cycle sends the plan first, as does a re-established session. Nav2's
        behaviour tree replans about once a second, and a raise here would end FollowPath at
        once, where a failing cycle gets the controller server's failure_tolerance. The
        planner's own errors (InvalidPath, ...) raise.
        """
        plan = path if isinstance(path, Plan) else Plan.from_msg(path)
        self._plan = plan.to_wire()
        self._plan_owed = True
        try:
            self._send_plan()
        except Nav2Error as exc:
            if not exc.host_failed:
                self._plan_owed = False
                raise
            log.warning("%s: plan kept, sent when the host answers: %s", self.keys.prefix, exc)
            return exc
        return None

    def follow(self, path: Plan | Any, goal: Any) -> None:
        """Lyrical: the plan controller_server transformed for this cycle and its global goal
        (PoseStamped), both in the costmap's global frame. Sends nothing: the next cycle
        carries each when it changed since the host got it (stamps aside), as the C++ plugin's
        ControllerSession::follow; a re-established session gets both with set_plan."""
        self._follows = True
        wire = (path if isinstance(path, Plan) else Plan.from_msg(path)).to_wire()
        goal_wire = pose_to_wire(goal)
        old_plan, old_goal = self._plan, self._goal
        if old_plan is None or (old_plan["frame_id"], old_plan["poses"]) != (
            wire["frame_id"],
            wire["poses"],
        ):
            self._plan = wire
            self._unsent.add("plan")
        if old_goal is None or (old_goal["frame_id"], old_goal["pose"]) != (
            goal_wire["frame_id"],
            goal_wire["pose"],
        ):
            self._goal = goal_wire
            self._unsent.add("goal")

    def _plan_body(self) -> dict[str, Any]:
        assert self._plan is not None
        body = {"path": self._plan}
        if self._goal is not None:
            body["goal"] = self._goal
        return body

    def _send_plan(self) -> None:
        self._call(Op.SET_PLAN, self._plan_body())
        self._plan_owed = False
        self._unsent.clear()

    def compute_velocity_commands(
        self,
        pose: Any,
        velocity: Any,
        goal_checker: GoalTolerances | None = None,
        inputs: Mapping[str, tuple[Any, int]] | None = None,
        debug_wanted: Iterable[str] = (),
    ) -> Any:
        """PoseStamped + Twist -> TwistStamped (finite, or an exception).

        inputs: new input messages, name -> (rclpy message, receive time [ns]), serialized
        as the plugin sends them; debug_wanted: debug outputs to return (into ``self.debug``).
        """
        body = self.compute_body(pose, velocity, goal_checker, inputs, debug_wanted)
        return self.command_of(self._compute(body))

    def _compute(self, body: dict[str, Any]) -> dict[str, Any]:
        """The compute_velocity_commands call with ``body``; its reply body."""
        if self._plan_owed:
            self._send_plan()  # a host failure here fails this cycle, as the cycle's own would
        carried = self._unsent.copy()
        if "plan" in carried:
            body = dict(body, plan=self._plan)
        if "goal" in carried:
            body = dict(body, goal=self._goal)
        reply = self._call(Op.COMPUTE_VELOCITY_COMMANDS, body)
        self._unsent -= carried
        return reply

    @staticmethod
    def compute_body(
        pose: Any,
        velocity: Any,
        goal_checker: GoalTolerances | None = None,
        inputs: Mapping[str, tuple[Any, int]] | None = None,
        debug_wanted: Iterable[str] = (),
    ) -> dict[str, Any]:
        """The compute_velocity_commands request body (without the costmap)."""
        body: dict[str, Any] = {"pose": pose_to_wire(pose), "velocity": twist_to_list(velocity)}
        if goal_checker is not None:
            body["goal_checker"] = goal_checker.to_wire()
        if inputs:
            body["inputs"] = [
                {"name": name, "type": type_name_of(msg), "stamp_ns": ns, "cdr": to_cdr(msg)}
                for name, (msg, ns) in inputs.items()
            ]
        wanted = list(debug_wanted)
        if wanted:
            body["debug_wanted"] = wanted
        return body

    def command_of(self, reply: dict[str, Any]) -> Any:
        """A compute_velocity_commands reply body -> its TwistStamped; its debug outputs into
        ``self.debug``."""
        self.debug = {d["name"]: from_cdr(d["type"], d["cdr"]) for d in reply.get("debug", [])}
        return twist_stamped_from_wire(reply["cmd_vel"])

    def set_speed_limit(self, speed_limit: float, percentage: bool) -> None:
        """Kept for a new session once the planner accepted it, and also when the host failed
        the call (a slow zone must survive a restart); one the planner refused is not."""
        try:
            self._call(Op.SET_SPEED_LIMIT, {"speed_limit": speed_limit, "percentage": percentage})
        except Nav2Error as exc:
            if exc.host_failed:
                self._speed_limit = (speed_limit, percentage)
            raise
        self._speed_limit = (speed_limit, percentage)

    def cancel(self) -> bool:
        cancelled: bool = self._call(Op.CANCEL, {})["cancelled"]
        return cancelled

    def reset(self) -> None:
        self._call(Op.RESET, {})

    def cleanup(self) -> None:
        self._plan, self._speed_limit, self._plan_owed = None, None, False
        self._goal, self._unsent, self._follows = None, set(), False
        super().cleanup()

    def _prepare(self, op: Op, body: dict[str, Any]) -> Carried | None:
        # A command prepared while the plan is owed, or before Nav2 transformed the cycle's
        # plan (Lyrical: after the goal check), would run on the host's old plan.
        if self._plan_owed or self._follows:
            return None
        return super()._prepare(op, body)

    def _take(
        self,
        carried: Carried | None,
        reply_bytes: bytes | None,
        body: dict[str, Any],
    ) -> dict[str, Any] | None:
        # A plan that became owed (set_plan sent nothing: no host) is news to the host too.
        if self._plan_owed or self._unsent:
            return None
        return super()._take(carried, reply_bytes, body)

    def _restored(self, op: Op) -> dict[str, Any] | None:
        if op is Op.SET_PLAN and self._plan is not None and not self._plan_owed:
            # (an owed plan is sent by the call that owes it, right after)
            self._unsent.clear()  # set_plan gives both the plan and the goal
            return self._plan_body()
        if op is Op.SET_SPEED_LIMIT and self._speed_limit is not None:
            limit, percentage = self._speed_limit
            return {"speed_limit": limit, "percentage": percentage}
        return None
