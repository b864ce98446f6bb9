"""Nav2's control cycle with Python checkers in fewer queries (PROTOCOL.md section 15).

controller_server calls, every cycle, the goal checker's ``isGoalReached(pose, goal,
velocity)``, the progress checker's ``check(pose)`` and the controller's
``computeVelocityCommands(pose, velocity, goal_checker)``, in one of two orders:

- goal check first (Jazzy from 1.3.13, Kilted, Lyrical): the goal check's query carries the
  check and the command, prepared for its pose and velocity; one round trip per cycle;
- goal check last (Humble, Jazzy 1.3.8 to 1.3.12): the check goes on its own, and the
  command's query carries the goal check, prepared for its pose and velocity and the goal the
  goal checker was last given; two round trips (one without a Python progress checker).

The order is learned from the calls: a goal check with the pose and velocity of the command
before it says "last", a command with those of the goal check before it says "first" (a robot
standing still says neither). A prepared request is used only when Nav2's call encodes to the
same bytes and nothing else went on that plugin's session since it was prepared
(``PluginClient._take``); otherwise the call goes on its own, so the results are always those
of Nav2's order. When TF moved on between the goal check's pose and the check's (goal check
first), the check goes on its own carrying the command prepared for its pose: two round trips.

Lyrical calls its path handler's ``findPlanSegment(pose)`` between the check and the command,
with the check's pose: a Python path handler's call rides with the goal check (or, when TF
moved on, the check), prepared like the command. Lyrical's command needs the segment's plan,
so it goes on its own there (PROTOCOL.md section 19).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from nav2_pyif_protocol.constants import Op

from nav2_pyif._messages import pose_to_wire, twist_to_list
from nav2_pyif.client.checkers import GoalCheckerClient, ProgressCheckerClient, pose7
from nav2_pyif.client.controller import ControllerClient
from nav2_pyif.client.path_handler import PathHandlerClient, segment_body, segment_of
from nav2_pyif.client.plugin_client import Body, Carried, PluginClient
from nav2_pyif.goal_tolerances import GoalTolerances

#: A request prepared for a carrier's query, and the reply that query brought back for it.
_Pending = tuple[Carried, bytes | None]


class ControlCycle:
    """A controller and its goal (and progress) checker, called in Nav2's order."""

    def __init__(
        self,
        controller: ControllerClient,
        goal_checker: GoalCheckerClient,
        progress_checker: ProgressCheckerClient | None = None,
        path_handler: PathHandlerClient | None = None,
    ) -> None:
        self.controller = controller
        self.goal_checker = goal_checker
        self.progress_checker = progress_checker
        self.path_handler = path_handler
        self._pending: dict[Op, _Pending] = {}
        self.goal_last = False  # the order learned: the goal check ends the cycle
        self._evidence = {"first": False, "last": False}
        self._goal_check: tuple[Any, ...] | None = None  # (pose7, velocity) of the last one
        self._command: tuple[Any, ...] | None = None  # likewise, of the last command
        self._goal: list[float] | None = None  # the goal the goal checker was last given
        self._goal_seq = -1  # the goal checker's seq after it: nothing sent since?
        self._compute_inputs: tuple[Any, ...] | None = None  # the goal check's, goal first
        self.carried_used = 0  # calls answered from a carried reply
        self.sent_alone = 0  # queries that carried nothing
        self.queries = 0  # queries sent, carrying or not

    def is_goal_reached(
        self,
        pose: Any,
        goal: Any,
        velocity: Any,
        tolerances: GoalTolerances | None = None,
        inputs: Mapping[str, tuple[Any, int]] | None = None,
        debug_wanted: Iterable[str] = (),
    ) -> bool:
        """``pose``: PoseStamped (the robot, global frame), ``goal``: Pose, ``velocity``:
        Twist; ``tolerances``: what the controller will be given (getTolerances); ``inputs``
        and ``debug_wanted``: what the controller's call will carry (ControllerClient's)."""
        body = {"pose": pose7(pose.pose), "goal": pose7(goal), "velocity": twist_to_list(velocity)}
        self._goal_check = (body["pose"], body["velocity"])
        self._learn("last", self._command == self._goal_check)
        answer = self._take(self.goal_checker, Op.IS_GOAL_REACHED, body)
        if answer is None:
            carry: list[tuple[PluginClient, Carried | None]] = []
            if not self.goal_last:
                self._compute_inputs = (pose, velocity, tolerances, inputs, debug_wanted)
                if self.progress_checker is not None:
                    check = self.progress_checker._prepare(Op.CHECK, {"pose": pose_to_wire(pose)})
                    carry.append((self.progress_checker, check))
                carry += self._prepare_rest(*self._compute_inputs)
            answer = self._send(self.goal_checker, Op.IS_GOAL_REACHED, body, carry)
        self._goal, self._goal_seq = body["goal"], self.goal_checker._seq
        reached: bool = answer["reached"]
        return reached

    def check(self, pose: Any) -> bool:
        """The progress checker's ``check(pose)``."""
        assert self.progress_checker is not None
        body = {"pose": pose_to_wire(pose)}
        answer = self._take(self.progress_checker, Op.CHECK, body)
        if answer is None:
            carry: list[tuple[PluginClient, Carried | None]] = []
            inputs, self._compute_inputs = self._compute_inputs, None
            moved = inputs is not None and pose_to_wire(inputs[0]) != body["pose"]
            if inputs is not None and moved and not self.goal_last:
                # TF moved on since the goal check: the calls prepared for it will not fit
                carry += self._prepare_rest(pose, *inputs[1:])
            answer = self._send(self.progress_checker, Op.CHECK, body, carry)
        progress: bool = answer["making_progress"]
        return progress

    def find_plan_segment(self, pose: Any) -> tuple[int, int]:
        """The path handler's ``find_plan_segment`` (Lyrical: after the check)."""
        assert self.path_handler is not None
        body = segment_body(pose)
        answer = self._take(self.path_handler, Op.FIND_PLAN_SEGMENT, body)
        if answer is None:
            answer = self._send(self.path_handler, Op.FIND_PLAN_SEGMENT, body, [])
        return segment_of(answer)

    def compute_velocity_commands(
        self,
        pose: Any,
        velocity: Any,
        tolerances: GoalTolerances | None = None,
        inputs: Mapping[str, tuple[Any, int]] | None = None,
        debug_wanted: Iterable[str] = (),
    ) -> Any:
        """The controller's ``compute_velocity_commands``."""
        self._compute_inputs = None
        body = self.controller.compute_body(pose, velocity, tolerances, inputs, debug_wanted)
        speed = body["velocity"]
        self._command = (pose7(pose.pose), speed)
        self._learn("first", self._goal_check == self._command)
        answer = self._take(self.controller, Op.COMPUTE_VELOCITY_COMMANDS, body)
        if answer is None:
            carry: list[tuple[PluginClient, Carried | None]] = []
            # the goal checker's last goal, unless it was reset since (a new plan, a new goal)
            if self.goal_last and self._goal and self.goal_checker._seq == self._goal_seq:
                goal_check = {"pose": self._command[0], "goal": self._goal, "velocity": speed}
                prepared = self.goal_checker._prepare(Op.IS_GOAL_REACHED, goal_check)
                carry.append((self.goal_checker, prepared))
            answer = self._send(self.controller, Op.COMPUTE_VELOCITY_COMMANDS, body, carry)
        return self.controller.command_of(answer)

    # --- the machinery ---------------------------------------------------------------------
    def _learn(self, order: str, seen: bool) -> None:
        """Evidence of the order: switch when this cycle matches one order and not the other."""
        self._evidence[order] = seen
        if self._evidence["last"] != self._evidence["first"]:
            self.goal_last = self._evidence["last"]

    def _prepare_rest(self, pose: Any, *inputs: Any) -> list[tuple[PluginClient, Carried | None]]:
        """The calls after the check, prepared for ``pose``: the path handler's segment
        (Lyrical; its command needs that segment, so it is not prepared), else the command."""
        if self.path_handler is not None:
            prepared = self.path_handler._prepare(Op.FIND_PLAN_SEGMENT, segment_body(pose))
            return [(self.path_handler, prepared)]
        return [(self.controller, self._prepare_command(pose, *inputs))]

    def _prepare_command(self, pose: Any, *inputs: Any) -> Carried | None:
        body = self.controller.compute_body(pose, *inputs)
        return self.controller._prepare(Op.COMPUTE_VELOCITY_COMMANDS, body)

    def _take(self, client: PluginClient, op: Op, body: Body) -> Body | None:
        """The carried reply of this call, when it was prepared for exactly this call."""
        carried, reply = self._pending.pop(op, (None, None))
        answer = client._take(carried, reply, body)
        self.carried_used += answer is not None
        return answer

    def _send(
        self,
        client: PluginClient,
        op: Op,
        body: Body,
        carry: list[tuple[PluginClient, Carried | None]],
    ) -> Body:
        """The call on its own query, carrying the requests prepared in ``carry``."""
        prepared = [(c, p) for c, p in carry if p is not None]
        if prepared:
            carried = [{"key": c.keys.prefix, "payload": p.payload} for c, p in prepared]
            body = dict(body, carry=carried)
        else:
            self.sent_alone += 1
        self.queries += 1
        if op is Op.COMPUTE_VELOCITY_COMMANDS:
            reply = self.controller._compute(body)
        else:
            reply = client._call(op, body)
        replies = [r["payload"] for r in reply.pop("carried", [])]
        for i, (_, request) in enumerate(prepared):
            self._pending[request.request.op] = (request, replies[i] if i < len(replies) else None)
        return reply
