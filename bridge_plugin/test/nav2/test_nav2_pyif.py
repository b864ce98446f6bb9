"""The first launch test: Nav2's controller_server and planner_server with the nav2_pyif
plugins, a lifecycle manager, a real planner host and a small simulated robot.

1. ComputePathToPose (Python A*) and FollowPath (Python regulated pure pursuit): the robot
   reaches the goal around a wall;
2. the host is killed (SIGKILL) mid-goal: the goal aborts with the matching error code and
   both servers stay active;
3. the host is restarted: the next goal succeeds (the plugins re-send their state).

Needs a sourced ROS 2 (rclpy, nav2_msgs) with Nav2's controller_server, planner_server and
lifecycle_manager, this package built and sourced (its pluginlib index), and a planner host:
`planner-host` on PATH or $NAV2_PYIF_PLANNER_HOST (a command, e.g. a wrapper that activates
the nav2_pyif venv). Skipped, saying what is missing, otherwise:

    source /opt/ros/jazzy/setup.bash && source install/setup.bash
    python -m pytest bridge_plugin/test/nav2 -v
"""

from __future__ import annotations

import math
import signal
import time
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

GOAL_A = (2.0, 0.5)  # behind the wall: the plan goes around it
GOAL_B = (0.0, 0.0)


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    yield from nav2_testing.bring_up(tmp_path_factory.mktemp("nav2_launch_test"))


SUCCEEDED, ABORTED = nav2_testing.SUCCEEDED, nav2_testing.ABORTED


def _drive_to(nav2: dict[str, Any], goal: tuple[float, float]) -> Any:
    client, procs = nav2["client"], nav2["procs"]
    planned = client.plan(*goal)
    logs = "\n".join(procs.log(n) for n in ("planner_server", "planner_host"))
    assert planned is not None, "no ComputePathToPose result\n" + logs
    code = nav2_testing.error_code(planned.result)
    assert planned.status == SUCCEEDED, f"planning failed: {code}\n{logs}"
    path = planned.result.path
    assert len(path.poses) > 10 and path.header.frame_id == "map"
    return path


def test_reaches_the_goal_survives_a_host_crash_and_recovers(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    servers = nav2_testing.SERVERS
    states = client.wait_active(servers, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + "\n".join(
        procs.log(n) for n in (*servers, "lifecycle_manager", "planner_host")
    )

    # 1. plan around the wall and follow the plan to the goal
    path = _drive_to(nav2, GOAL_A)
    assert min(p.pose.position.y for p in path.poses) < -0.6, "the plan does not avoid the wall"
    handle = client.follow(path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    assert client.spin_until(lambda: client.pose is not None, 5.0)
    x, y = client.pose
    assert math.hypot(x - GOAL_A[0], y - GOAL_A[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL_A}"

    # parameters: the planner's own are declared on the node; `ros2 param set` reaches it
    names = client.list_parameters("controller_server", "FollowPath")
    assert "FollowPath.desired_linear_vel" in names  # from the YAML
    assert "FollowPath.max_lookahead_dist" in names  # declared by the Python planner
    assert client.set_parameter("controller_server", "FollowPath.desired_linear_vel", 0.45) == (
        True,
        "",
    )
    ok, reason = client.set_parameter("controller_server", "FollowPath.desired_linear_vel", "x")
    assert not ok and "desired_linear_vel" in reason, reason  # the planner refused it
    ok, reason = client.set_parameter("controller_server", "FollowPath.timeout", 0.4)
    assert ok, reason  # a bridge setting the plugin applies itself

    # 2. the host dies mid-goal: the goal aborts with the plugin's error code, Nav2 stays up
    handle = client.follow(_drive_to(nav2, GOAL_B))
    client.spin_until(lambda: False, 1.5)  # driving
    procs.kill("planner_host", signal.SIGKILL)
    killed = time.monotonic()
    result = client.wait(handle.get_result_async(), 30.0)
    logs = procs.log("controller_server")
    assert result is not None and result.status == ABORTED, f"FollowPath: {result}\n{logs}"

    # No reply in time while the dead host's token lingers, or no host alive once it is gone:
    # either way NoValidControl, which the default BT's WouldAControllerRecoveryHelp retries
    # (failure_tolerance is 0 here, so the goal aborts at once).
    nav2_testing.assert_error_code(result.result, "NO_VALID_CONTROL", logs)
    assert time.monotonic() - killed < 5.0, "the abort took longer than a few timeouts"
    assert client.wait_active(servers, 10.0) == dict.fromkeys(servers, "active")
    assert procs.alive("controller_server") and procs.alive("planner_server")

    # 3. a new host: the next goal succeeds, once the controller's plugin sees it (zenoh-pico
    # re-joins a host it dials directly once a second)
    started = nav2["start_host"]()
    alive = f"is alive on {nav2_testing.PREFIX}/FollowPath"
    assert client.spin_until(lambda: procs.logged_at("controller_server", alive, started), 30.0), (
        procs.log("controller_server")
    )
    deadline = time.monotonic() + 60.0
    planned = None
    while time.monotonic() < deadline:  # until the plugin sees the new host
        planned = client.plan(*GOAL_B)
        if planned is not None and planned.status == SUCCEEDED:
            break
        client.spin_until(lambda: False, 1.0)
    assert planned is not None and planned.status == SUCCEEDED, procs.log("planner_server")
    handle = client.follow(planned.result.path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL_B[0], y - GOAL_B[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL_B}"
