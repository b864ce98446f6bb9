"""Nav2's control cycle with Python checkers in fewer queries (PROTOCOL.md section 15), in
both of controller_server's orders, through real planner-host processes over real Zenoh
sessions on loopback."""

from __future__ import annotations

from typing import Any

import msgpack
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif._messages import pose_to_wire
from nav2_pyif.client import (
    ControlCycle,
    ControllerClient,
    GoalCheckerClient,
    ProgressCheckerClient,
)
from nav2_pyif_protocol.codec import decode_reply
from nav2_pyif_protocol.constants import ErrorType, Op
from nav2_pyif_protocol.keys import KeySpace

from tests.conftest import make_costmap
from tests.test_smoother_and_checker_hosts import GENEROUS, no_costmap, pose, stamped

pytestmark = pytest.mark.integration

CONTROLLER = "nav2_pyif/test_robot/FollowPath"
GOAL = "nav2_pyif/test_robot/goal_checker"
PROGRESS = "nav2_pyif/test_robot/progress_checker"
CHECKERS = "nav2_pyif_planners.checker_plugins"


def cycle_on(zsession_factory: Any, hosts: dict[str, Any], progress: bool = True) -> ControlCycle:
    """The three plugins (two without ``progress``), each talking to the host serving its key."""

    def client(cls: Any, key: str, **kw: Any) -> Any:
        made = cls(zsession_factory(hosts[key].endpoint), key, timeouts=GENEROUS, **kw)
        assert made.wait_for_host(15), hosts[key].log()
        made.configure()
        return made

    controller = client(ControllerClient, CONTROLLER, costmap=make_costmap())
    controller.activate()
    return ControlCycle(
        controller,
        client(GoalCheckerClient, GOAL, costmap=make_costmap()),
        client(ProgressCheckerClient, PROGRESS, costmap=no_costmap()) if progress else None,
    )


def serving_the_cycle(controller: str, goal: str, progress: str) -> list[str]:
    """planner-host arguments: one host serving a counting controller and the two checkers."""
    return [
        "--key",
        controller,
        "--planner",
        "echo_planners:EchoController",
        "--serve",
        f"{goal}={CHECKERS}:StoppedGoalChecker",
        "--serve",
        f"{progress}={CHECKERS}:SimpleProgressChecker",
    ]


def one_host(start_host: Any) -> dict[str, Any]:
    host = start_host(*serving_the_cycle(CONTROLLER, GOAL, PROGRESS))
    return dict.fromkeys((CONTROLLER, GOAL, PROGRESS), host)


def queries_by_key(session: Any) -> dict[str, int]:
    """The queries the host answered on each of the three keys (what `nav2-pyif hosts` shows)."""
    counts = {}
    for key in (CONTROLLER, GOAL, PROGRESS):
        replies = list(session.get(KeySpace(key).admin_info, timeout=5.0))
        counts[key] = msgpack.unpackb(replies[0].ok.payload.to_bytes())["queries"]
    return counts


def calls(cmd: Any) -> int:
    return int(cmd.twist.angular.z)  # EchoController counts its compute_velocity_commands


def test_one_query_per_cycle_when_one_host_serves_all_three(
    start_host: Any, zsession_factory: Any
) -> None:
    cycle = cycle_on(zsession_factory, one_host(start_host))
    goal = pose(2.5, 0.5)
    tolerances = cycle.goal_checker.get_tolerances()
    for step in range(3):
        robot = stamped(0.5 + 0.6 * step, 0.5, 100.0 + step)
        assert not cycle.is_goal_reached(robot, goal, Twist(), tolerances)
        assert cycle.check(robot)
        cmd = cycle.compute_velocity_commands(robot, Twist(), tolerances)
        assert calls(cmd) == step + 1  # the controller ran once per cycle
        assert cmd.twist.angular.y == 0.0  # the costmap travelled: free cell at the pose
    assert (cycle.carried_used, cycle.sent_alone) == (6, 0)
    # the goal reached: Nav2 stops, and so does the host: nothing else ran
    robot = stamped(2.6, 0.5, 104.0)
    assert cycle.is_goal_reached(robot, goal, Twist(), tolerances)
    alone = cycle.controller.compute_velocity_commands(robot, Twist(), tolerances)
    assert calls(alone) == 4


@pytest.mark.parametrize("lag", [0.0, 0.01], ids=["same pose", "TF moved on"])
def test_no_progress_stops_the_cycle_before_the_controller(
    start_host: Any, zsession_factory: Any, lag: float
) -> None:
    """``lag``: Nav2's second pose lookup is that much newer than the goal check's, so the
    check goes on its own carrying the command (which ran only when making progress)."""
    cycle = cycle_on(zsession_factory, one_host(start_host))
    goal = pose(3.0, 0.5)
    extra = 1 if lag else 0  # the command carried by the goal check, run and unused
    robot = stamped(0.5, 0.5, 100.0)
    assert not cycle.is_goal_reached(robot, goal, Twist())
    robot = stamped(0.5, 0.5, 100.0 + lag)
    assert cycle.check(robot)
    assert calls(cycle.compute_velocity_commands(robot, Twist())) == 1 + extra
    assert not cycle.is_goal_reached(stamped(0.6, 0.5, 111.0), goal, Twist())
    stuck = stamped(0.6, 0.5, 111.0 + lag)  # 11 s later, 0.1 m on: no progress
    assert not cycle.check(stuck)  # controller_server throws FailedToMakeProgress here
    # no command ran in this cycle: the controller's next call follows the first cycle's
    assert calls(cycle.controller.compute_velocity_commands(stuck, Twist())) == 2 + extra


def test_other_inputs_or_another_host_fall_back_to_calls_of_their_own(
    start_host: Any, zsession_factory: Any
) -> None:
    hosts = one_host(start_host)
    hosts[CONTROLLER] = start_host("--key", CONTROLLER, "--planner", "echo_planners:EchoController")
    checkers = hosts[GOAL]
    hosts[GOAL] = hosts[PROGRESS] = checkers
    cycle = cycle_on(zsession_factory, hosts)
    goal = pose(3.0, 0.5)
    robot = stamped(0.5, 0.5, 100.0)
    # the checkers' host serves a controller too, but not the one this plugin talks to:
    # its carried compute ran there on a session it does not know, so it goes on its own
    assert not cycle.is_goal_reached(robot, goal, Twist())
    assert cycle.check(robot)
    assert calls(cycle.compute_velocity_commands(robot, Twist())) == 1
    assert (cycle.carried_used, cycle.sent_alone, cycle.queries) == (1, 1, 2)
    # Nav2 looked the pose up again and it moved: the check goes on its own, carrying the
    # command prepared for the moved pose, which its host (not the controller's) cannot run
    assert not cycle.is_goal_reached(stamped(0.6, 0.5, 100.1), goal, Twist())
    moved = stamped(0.7, 0.5, 100.11)
    assert cycle.check(moved)
    assert calls(cycle.compute_velocity_commands(moved, Twist())) == 2
    assert (cycle.carried_used, cycle.sent_alone, cycle.queries) == (1, 2, 5)


def test_a_pose_that_moved_after_the_goal_check_costs_two_queries_not_three(
    start_host: Any, zsession_factory: Any
) -> None:
    hosts = one_host(start_host)
    cycle = cycle_on(zsession_factory, hosts)
    goal = pose(3.0, 0.5)
    tolerances = cycle.goal_checker.get_tolerances()
    session = zsession_factory(hosts[CONTROLLER].endpoint)
    before = queries_by_key(session)
    for step in range(3):
        robot = stamped(0.5 + 0.3 * step, 0.5, 100.0 + step)
        moved = stamped(0.55 + 0.3 * step, 0.5, 100.02 + step)  # TF moved on meanwhile
        assert not cycle.is_goal_reached(robot, goal, Twist(), tolerances)
        assert cycle.check(moved)
        cmd = cycle.compute_velocity_commands(moved, Twist(), tolerances)
        # the controller ran for the goal check's pose (carried, unused) and for the moved
        # one (carried by the check): the command is the moved pose's, in Nav2's order
        assert calls(cmd) == 2 * (step + 1)
    # each cycle: the goal check's query and the check's, the command answered from the latter
    assert (cycle.carried_used, cycle.queries) == (3, 6)
    sent = {k: v - before[k] for k, v in queries_by_key(session).items()}
    assert sent == {GOAL: 3, PROGRESS: 3, CONTROLLER: 0}, sent


def drive(cycle: ControlCycle, goal_last: bool, robot: Any, goal: Any) -> list[Any]:
    """One control cycle in controller_server's order (``goal_last``: Humble's); what each
    call answered, up to where Nav2 stops (the goal reached)."""
    seen: list[Any] = []

    def goal_check() -> bool:
        seen.append(cycle.is_goal_reached(robot, goal, Twist()))
        return bool(seen[-1])

    if not goal_last and goal_check():
        return seen
    if cycle.progress_checker is not None:
        seen.append(cycle.check(robot))
    cmd = cycle.compute_velocity_commands(robot, Twist())
    seen.append(cmd)  # rclpy messages compare by value
    if goal_last:
        goal_check()
    return seen


class Uncarried(ControlCycle):
    """The same plugins, each call on its own: what Nav2's calls give without carrying."""

    def is_goal_reached(self, pose: Any, goal: Any, velocity: Any, *_: Any) -> bool:
        return self.goal_checker.is_goal_reached(pose.pose, goal, velocity)

    def check(self, pose: Any) -> bool:
        assert self.progress_checker is not None
        return self.progress_checker.check(pose)

    def compute_velocity_commands(self, pose: Any, velocity: Any, *_: Any) -> Any:
        return self.controller.compute_velocity_commands(pose, velocity)


@pytest.mark.parametrize("progress", [True, False], ids=["both checkers", "goal checker only"])
@pytest.mark.parametrize("goal_last", [False, True], ids=["goal check first", "goal check last"])
def test_each_order_costs_its_queries_and_answers_as_uncarried_calls(
    start_host: Any, zsession_factory: Any, goal_last: bool, progress: bool
) -> None:
    hosts = one_host(start_host)
    cycle = cycle_on(zsession_factory, hosts, progress)
    plain = cycle_on(zsession_factory, hosts, progress)  # sessions of their own on that host
    uncarried = Uncarried(plain.controller, plain.goal_checker, plain.progress_checker)
    session = zsession_factory(hosts[CONTROLLER].endpoint)
    before = queries_by_key(session)
    goal, steps = pose(2.0, 0.5), 5
    for step in range(steps):  # the robot moves on between cycles; the last one arrives
        robot = stamped(0.5 + 0.375 * step, 0.5, 100.0 + step)
        seen = drive(cycle, goal_last, robot, goal)
        assert seen == drive(uncarried, goal_last, robot, goal), step
    assert seen[-1 if goal_last else 0] is True  # reached: both stopped there
    sent = sum(v - before[k] for k, v in queries_by_key(session).items())
    sent -= uncarried_queries(steps, goal_last, progress)
    # goal first: the goal check carries the rest. Goal last: the first goal check shows the
    # order; from then on the command carries the goal check, the check goes on its own.
    assert sent == (steps if not goal_last else (2 if progress else 1) * steps + 1), sent
    assert cycle.goal_last is goal_last


def uncarried_queries(steps: int, goal_last: bool, progress: bool) -> int:
    """Queries the uncarried calls sent: a query per call, none after the goal is reached."""
    per_cycle = 3 if progress else 2
    return per_cycle * steps - (0 if goal_last else per_cycle - 1)


def test_goal_last_a_reset_or_a_moved_pose_sends_the_goal_check_on_its_own(
    start_host: Any, zsession_factory: Any
) -> None:
    """Goal check last: the carried goal check is for the goal the checker was last given,
    so not after a reset (controller_server resets it with every new plan), and used only
    when Nav2's goal check has the command's pose and velocity."""
    cycle = cycle_on(zsession_factory, one_host(start_host), progress=False)
    goal = pose(3.0, 0.5)
    for step in range(2):  # learn the order, then a carried cycle
        robot = stamped(0.5 + 0.3 * step, 0.5, 100.0 + step)
        drive(cycle, True, robot, goal)
    assert (cycle.carried_used, cycle.queries) == (1, 3)
    cycle.goal_checker.reset()  # a new plan: the next command carries no goal check
    drive(cycle, True, stamped(1.1, 0.5, 102.0), goal)
    assert (cycle.carried_used, cycle.queries) == (1, 5)
    drive(cycle, True, stamped(1.4, 0.5, 103.0), goal)
    assert (cycle.carried_used, cycle.queries) == (2, 6)
    # TF moved on between the command's pose lookup and the goal check's: on its own
    cycle.compute_velocity_commands(stamped(1.7, 0.5, 104.0), Twist())
    assert not cycle.is_goal_reached(stamped(1.75, 0.5, 104.01), goal, Twist())
    assert (cycle.carried_used, cycle.queries) == (2, 8)
    assert cycle.goal_last  # one cycle that fits neither order changes nothing


def test_the_host_runs_only_what_the_schema_lets_a_call_carry(
    start_host: Any, zsession_factory: Any
) -> None:
    """schema.CARRIES: a command may carry the goal check, not the progress check."""
    cycle = cycle_on(zsession_factory, one_host(start_host))
    assert cycle.progress_checker is not None
    robot = stamped(0.5, 0.5, 100.0)
    check = cycle.progress_checker._prepare(Op.CHECK, {"pose": pose_to_wire(robot)})
    assert check is not None
    body = cycle.controller.compute_body(robot, Twist())
    body["carry"] = [{"key": PROGRESS, "payload": check.payload}]
    reply = cycle.controller._compute(body)
    (carried,) = reply["carried"]
    answer = decode_reply(carried["payload"], Op.CHECK)
    assert answer.error is not None and answer.error.type == ErrorType.BAD_REQUEST.value
    assert "compute_velocity_commands may not carry check" in answer.error.message
