"""Nav2's control cycle with Python checkers in one query (PROTOCOL.md section 15), through
real planner-host processes over real Zenoh sessions on loopback."""

from __future__ import annotations

from typing import Any

from geometry_msgs.msg import Twist
from nav2_pyif.client import (
    ControlCycle,
    ControllerClient,
    GoalCheckerClient,
    ProgressCheckerClient,
)

from tests.conftest import make_costmap
from tests.test_smoother_and_checker_hosts import GENEROUS, no_costmap, pose, stamped

CONTROLLER = "nav2_pyif/test_robot/FollowPath"
GOAL = "nav2_pyif/test_robot/goal_checker"
PROGRESS = "nav2_pyif/test_robot/progress_checker"
CHECKERS = "nav2_pyif_planners.checker_plugins"


def cycle_on(zsession_factory: Any, hosts: dict[str, Any]) -> ControlCycle:
    """The three plugins, each talking to the host serving its key."""

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
        client(ProgressCheckerClient, PROGRESS, costmap=no_costmap()),
    )


def one_host(start_host: Any) -> dict[str, Any]:
    host = start_host(
        "--key",
        CONTROLLER,
        "--planner",
        "echo_planners:EchoController",
        "--serve",
        f"{GOAL}={CHECKERS}:StoppedGoalChecker",
        "--serve",
        f"{PROGRESS}={CHECKERS}:SimpleProgressChecker",
    )
    return dict.fromkeys((CONTROLLER, GOAL, PROGRESS), host)


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


def test_no_progress_stops_the_cycle_before_the_controller(
    start_host: Any, zsession_factory: Any
) -> None:
    cycle = cycle_on(zsession_factory, one_host(start_host))
    goal = pose(3.0, 0.5)
    robot = stamped(0.5, 0.5, 100.0)
    assert not cycle.is_goal_reached(robot, goal, Twist())
    assert cycle.check(robot)
    assert calls(cycle.compute_velocity_commands(robot, Twist())) == 1
    stuck = stamped(0.6, 0.5, 111.0)  # 11 s later, 0.1 m on: no progress
    assert not cycle.is_goal_reached(stuck, goal, Twist())
    assert not cycle.check(stuck)  # controller_server throws FailedToMakeProgress here
    assert calls(cycle.controller.compute_velocity_commands(stuck, Twist())) == 2


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
    assert (cycle.carried_used, cycle.sent_alone) == (1, 1)
    # Nav2 looked the pose up again and it moved: both calls go on their own
    assert not cycle.is_goal_reached(robot, goal, Twist())
    moved = stamped(0.7, 0.5, 100.1)
    assert cycle.check(moved)
    assert calls(cycle.compute_velocity_commands(moved, Twist())) == 2
    assert (cycle.carried_used, cycle.sent_alone) == (1, 3)
