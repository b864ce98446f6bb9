"""Nav2's control cycle with Python checkers in one query (PROTOCOL.md section 15).

controller_server (Jazzy) calls, every cycle: the goal checker's ``isGoalReached(pose, goal,
velocity)``, then (not reached) the progress checker's ``check(pose)``, then (progress) the
controller's ``computeVelocityCommands(pose, velocity, goal_checker)``; three round trips
when each is its own query. Here the goal check carries the other two, prepared for the same
pose and velocity; the host runs them in that order, as far as Nav2 would go. When Nav2 then
makes those calls with the inputs they were prepared for (it looks the pose up again, which
is nearly always the same), their carried replies are used: one round trip per cycle. With
other inputs, or when a carried call did not run (another host, an unknown session), the call
goes on its own, so the results are always those of Nav2's order. When TF moved on between
the goal check's pose and the progress check's, the progress check goes on its own carrying
the command, prepared for its pose (Nav2 gives both the same pose): two round trips.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from nav2_pyif_protocol.constants import Op

from nav2_pyif.client.checkers import GoalCheckerClient, ProgressCheckerClient, pose7
from nav2_pyif.client.controller import ControllerClient
from nav2_pyif.client.plugin_client import Carried
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.messages import pose_to_wire, twist_to_list


@dataclass
class _Pending:
    pose: dict[str, Any]
    compute_body: dict[str, Any]
    check: tuple[Carried, bytes | None] | None
    compute: tuple[Carried, bytes | None] | None
    # The goal check's velocity, tolerances, inputs and debug_wanted: the command's inputs
    # other than the pose, for a command the progress check carries instead.
    compute_inputs: tuple[Any, ...]


class ControlCycle:
    """A controller and its goal (and progress) checker, called in Nav2's order."""

    def __init__(
        self,
        controller: ControllerClient,
        goal_checker: GoalCheckerClient,
        progress_checker: ProgressCheckerClient | None = None,
    ) -> None:
        self.controller = controller
        self.goal_checker = goal_checker
        self.progress_checker = progress_checker
        self._pending: _Pending | None = None
        self.carried_used = 0  # calls answered from a carried reply
        self.sent_alone = 0  # calls that went on their own

    def is_goal_reached(
        self,
        pose: Any,
        goal: Any,
        velocity: Any,
        tolerances: GoalChecker | None = None,
        inputs: Mapping[str, tuple[Any, int]] | None = None,
        debug_wanted: Iterable[str] = (),
    ) -> bool:
        """``pose``: PoseStamped (the robot, global frame), ``goal``: Pose, ``velocity``:
        Twist; ``tolerances``: what the controller will be given (getTolerances); ``inputs``
        and ``debug_wanted``: what the controller's call will carry (ControllerClient's)."""
        wire_pose, speed = pose_to_wire(pose), twist_to_list(velocity)
        body: dict[str, Any] = {"pose": pose7(pose.pose), "goal": pose7(goal), "velocity": speed}
        check = None
        if self.progress_checker is not None:
            check = self.progress_checker._prepare(Op.CHECK, {"pose": wire_pose})
            if check is not None:
                body["then_check_key"] = self.progress_checker.keys.prefix
                body["then_check"] = check.payload
        compute_inputs = (velocity, tolerances, inputs, debug_wanted)
        compute_body, compute = self._carry_compute(body, pose, compute_inputs)
        self._pending = None
        reply = self.goal_checker._call(Op.IS_GOAL_REACHED, body)
        self._pending = _Pending(
            wire_pose,
            compute_body,
            None if check is None else (check, reply.get("then_check")),
            None if compute is None else (compute, reply.get("then_compute")),
            compute_inputs,
        )
        reached: bool = reply["reached"]
        return reached

    def _carry_compute(
        self, body: dict[str, Any], pose: Any, compute_inputs: tuple[Any, ...]
    ) -> tuple[dict[str, Any], Carried | None]:
        """The command's body for ``pose``, and its request added to ``body`` to be carried."""
        compute_body = self.controller.compute_body(pose, *compute_inputs)
        compute = self.controller._prepare(
            Op.COMPUTE_VELOCITY_COMMANDS, compute_body, with_costmap=True
        )
        if compute is not None:
            body["then_compute_key"] = self.controller.keys.prefix
            body["then_compute"] = compute.payload
        return compute_body, compute

    def check(self, pose: Any) -> bool:
        """The progress checker's ``check(pose)``."""
        assert self.progress_checker is not None
        pending = self._pending
        same_pose = pending is not None and pose_to_wire(pose) == pending.pose
        carried = pending.check if pending and same_pose else None
        if pending is not None:
            pending.check = None
        body = self.progress_checker._settle(*carried) if carried else None
        if body is None:
            self.sent_alone += 1
            if pending is None or same_pose:  # the goal check's command still fits
                return self.progress_checker.check(pose)
            return self._check_carrying_the_command(pose, pending)
        self.carried_used += 1
        progress: bool = body["making_progress"]
        return progress

    def _check_carrying_the_command(self, pose: Any, pending: _Pending) -> bool:
        """The check on its own, carrying the command prepared for its pose."""
        assert self.progress_checker is not None
        body: dict[str, Any] = {"pose": pose_to_wire(pose)}
        pending.compute_body, compute = self._carry_compute(body, pose, pending.compute_inputs)
        pending.compute = None
        reply = self.progress_checker._call(Op.CHECK, body)
        if compute is not None:
            pending.compute = (compute, reply.get("then_compute"))
        progress: bool = reply["making_progress"]
        return progress

    def compute_velocity_commands(
        self,
        pose: Any,
        velocity: Any,
        tolerances: GoalChecker | None = None,
        inputs: Mapping[str, tuple[Any, int]] | None = None,
        debug_wanted: Iterable[str] = (),
    ) -> Any:
        """The controller's ``compute_velocity_commands``."""
        pending, self._pending = self._pending, None
        carried = None
        body = self.controller.compute_body(pose, velocity, tolerances, inputs, debug_wanted)
        if (
            pending is not None
            and body == pending.compute_body
            and pending.compute is not None
            and pending.compute[0].costmap_version == self.controller.costmap.version
        ):
            carried = pending.compute
        reply = self.controller._settle(*carried) if carried else None
        if reply is None:
            self.sent_alone += 1
            return self.controller.compute_velocity_commands(
                pose, velocity, tolerances, inputs, debug_wanted
            )
        self.carried_used += 1
        return self.controller.command_of(reply)
