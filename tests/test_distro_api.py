"""One Python API on every distribution, for what Nav2 Lyrical adds (PROTOCOL.md section 14),
through real planner-host processes over real Zenoh sessions on loopback:

- a controller follows the plan controller_server transformed and its global goal, sent
  with a cycle only when they changed, and restored on a restarted worker from the journal;
  on Humble and Jazzy (set_plan) its global goal is the plan's last pose;
- a planner gets the viapoints (none before Lyrical);
- a goal checker serves isGoalXYReached with a default, and the path length tolerance.
"""

from __future__ import annotations

import math
import os
import signal
import time
from typing import Any

import numpy as np
import pytest
from geometry_msgs.msg import Pose, PoseStamped, Twist
from nav2_pyif import GoalTolerances, Plan
from nav2_pyif.client import (
    ControllerClient,
    GlobalPlannerClient,
    GoalCheckerClient,
    PluginClient,
    Timeouts,
)

from tests.conftest import make_costmap, wait_until, worker_pid_in

pytestmark = pytest.mark.integration

CONTROLLER = "nav2_pyif/test_robot/FollowPath"
PLANNER = "nav2_pyif/test_robot/GridBased"
CHECKER = "nav2_pyif/test_robot/goal_checker"
GENEROUS = Timeouts(call=2.0, lifecycle=5.0, configure=10.0, plan=5.0)


def connect(cls: type[PluginClient], zsession_factory: Any, host: Any, key: str, **kw: Any) -> Any:
    session = zsession_factory(host.endpoint)
    client = cls(session, key, make_costmap(), timeouts=GENEROUS, **kw)
    assert client.wait_for_host(15), host.log()
    client.configure()
    client.activate()
    return client


def stamped(x: float, y: float, frame: str = "odom", stamp_ns: int = 0) -> Any:
    msg = PoseStamped()
    msg.header.frame_id = frame
    msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    msg.pose.position.x, msg.pose.position.y = x, y
    msg.pose.orientation.w = 1.0
    return msg


def pose(x: float, y: float, yaw: float = 0.0) -> Any:
    msg = Pose()
    msg.position.x, msg.position.y = x, y
    msg.orientation.z, msg.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return msg


def straight(n: int, stamp_ns: int = 0) -> Plan:
    return Plan(np.column_stack([np.linspace(0.0, 3.0, n), np.zeros(n)]), "odom", stamp_ns)


def report(cmd: Any) -> tuple[float, float, float, float]:
    """PlanReport's command: (plan poses, global goal x, set_plan calls, path length tol)."""
    lin = cmd.twist.linear
    return lin.x, lin.y, lin.z, cmd.twist.angular.z


def test_a_controller_follows_the_transformed_plan_sent_only_when_it_changed(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", CONTROLLER, "--planner", "distro_api:PlanReport")
    client = connect(ControllerClient, zsession_factory, host, CONTROLLER, record_calls=True)
    checker = GoalTolerances(0.25, 0.25, 0.1, 0.1, path_length_tolerance=1.0)

    client.follow(straight(40), stamped(5.0, 0.0))
    assert report(client.compute_velocity_commands(stamped(0, 0), Twist(), checker)) == (
        40.0,
        5.0,
        1.0,
        1.0,
    )
    # the next cycle: stamped anew, the same plan and goal: nothing re-sent
    client.follow(straight(40, stamp_ns=50_000_000), stamped(5.0, 0.0, stamp_ns=50_000_000))
    assert report(client.compute_velocity_commands(stamped(0, 0), Twist())) == (
        40.0,
        5.0,
        1.0,
        -1.0,
    )
    # pruned as the robot moves on; the goal unchanged
    client.follow(straight(31), stamped(5.0, 0.0))
    assert report(client.compute_velocity_commands(stamped(0.5, 0), Twist()))[:3] == (
        31.0,
        5.0,
        2.0,
    )
    # the goal alone moved (localisation): the same plan, no set_plan
    client.follow(straight(31), stamped(5.1, 0.0))
    assert report(client.compute_velocity_commands(stamped(0.5, 0), Twist()))[:3] == (
        31.0,
        5.1,
        2.0,
    )
    cycles = [r for r in client.records if r.op == "compute_velocity_commands"]
    sizes = [r.request_bytes for r in cycles]
    assert sizes[1] < sizes[0] and sizes[2] > sizes[1] and sizes[3] < sizes[2], sizes

    # a killed worker: the journal gives the new one the plan and the goal the cycles carried
    first = worker_pid_in(host.log(), CONTROLLER)
    assert first is not None
    os.kill(first, signal.SIGKILL)
    assert wait_until(lambda: worker_pid_in(host.log(), CONTROLLER) not in (first, None), 30)
    time.sleep(0.2)
    assert report(client.compute_velocity_commands(stamped(0.5, 0), Twist()))[:3] == (
        31.0,
        5.1,
        1.0,
    )
    assert client.resyncs == 0


def test_before_lyrical_the_global_goal_is_the_plans_last_pose(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", CONTROLLER, "--planner", "distro_api:PlanReport")
    client = connect(ControllerClient, zsession_factory, host, CONTROLLER)
    client.set_plan(straight(12))
    assert report(client.compute_velocity_commands(stamped(0, 0), Twist())) == (
        12.0,
        3.0,
        1.0,
        -1.0,
    )


def test_viapoints_reach_a_python_planner(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", PLANNER, "--planner", "distro_api:ThroughViapoints")
    client = connect(GlobalPlannerClient, zsession_factory, host, PLANNER)
    start, goal = stamped(0.0, 0.0, "map"), stamped(4.0, 0.0, "map")
    via = [stamped(1.0, 2.0, "map"), stamped(3.0, -1.0, "map")]
    plan = client.create_plan(start, goal, viapoints=via)
    np.testing.assert_allclose(plan.xy, [[0, 0], [1, 2], [3, -1], [4, 0]])
    # none (Humble, Jazzy, or Lyrical without viapoints): the attribute is empty again
    np.testing.assert_allclose(client.create_plan(start, goal).xy, [[0, 0], [4, 0]])


def test_goal_checkers_serve_is_goal_xy_reached_and_the_path_length_tolerance(
    start_host: Any, zsession_factory: Any
) -> None:
    other = "nav2_pyif/test_robot/other_checker"
    host = start_host(
        "--key",
        CHECKER,
        "--planner",
        "distro_api:StrictYaw",
        "--serve",
        f"{other}=distro_api:NoTolerances",
    )
    client = connect(GoalCheckerClient, zsession_factory, host, CHECKER)
    goal = pose(2.0, 1.0)
    turned = pose(2.2, 1.0, yaw=1.0)  # within 0.3 m, heading off
    assert not client.is_goal_reached(turned, goal, Twist())
    assert client.is_goal_xy_reached(turned, goal, Twist())  # the default: xy tolerance only
    assert not client.is_goal_xy_reached(pose(2.5, 1.0), goal, Twist())
    assert client.get_tolerances() == GoalTolerances(0.3, 0.1, 0.05, 0.05, 1.5)

    bare = connect(GoalCheckerClient, zsession_factory, host, other)
    assert bare.get_tolerances() is None
    assert not bare.is_goal_xy_reached(turned, goal, Twist())  # falls back on is_goal_reached
    assert bare.is_goal_xy_reached(goal, goal, Twist())
