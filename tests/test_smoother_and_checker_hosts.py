"""Smoothers, goal checkers and progress checkers served by real planner-host processes over
real Zenoh sessions on loopback: the reference plugins, both planner styles, typed errors,
worker crashes restored from the journal, hot swap."""

from __future__ import annotations

import math
import os
import signal
import time
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import Pose, PoseStamped, Twist
from nav2_pyif import Costmap, GoalTolerances, Plan
from nav2_pyif._messages import ns_to_stamp
from nav2_pyif.client import (
    GoalCheckerClient,
    PluginClient,
    ProgressCheckerClient,
    SmootherClient,
    Timeouts,
)
from nav2_pyif.tools.admin import request_reload

from tests.conftest import make_costmap, wait_until, worker_pid_in

pytestmark = pytest.mark.integration

SMOOTHER = "nav2_pyif/test_robot/simple_smoother"
GOAL = "nav2_pyif/test_robot/goal_checker"
PROGRESS = "nav2_pyif/test_robot/progress_checker"
GENEROUS = Timeouts(call=2.0, lifecycle=5.0, configure=10.0, plan=5.0)
ZIGZAG = Plan(np.column_stack([np.linspace(0.2, 1.8, 17), 0.5 + 0.05 * (np.arange(17) % 2)]), "map")


def no_costmap() -> Costmap:
    """What a progress checker's plugin sends: Nav2 gives it no costmap."""
    return Costmap(np.zeros((0, 0), np.uint8), 1.0, frame_id="odom")


def connect(cls: type[PluginClient], zsession_factory: Any, host: Any, key: str, **kw: Any) -> Any:
    kw.setdefault("timeouts", GENEROUS)
    costmap = kw.pop("costmap", make_costmap(frame="map"))
    client = cls(zsession_factory(host.endpoint), key, costmap, **kw)
    assert client.wait_for_host(15), host.log()
    return client


def pose(x: float, y: float, yaw: float = 0.0) -> Any:
    msg = Pose()
    msg.position.x, msg.position.y = x, y
    msg.orientation.z, msg.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return msg


def twist(vx: float = 0.0, wz: float = 0.0) -> Any:
    msg = Twist()
    msg.linear.x, msg.angular.z = vx, wz
    return msg


def stamped(x: float, y: float, t: float) -> Any:
    msg = PoseStamped(pose=pose(x, y))
    msg.header.frame_id = "odom"
    msg.header.stamp = ns_to_stamp(int(t * 1e9))
    return msg


def test_simple_smoother_smooths_with_nav2s_parameters(
    start_host: Any, zsession_factory: Any
) -> None:
    spec = "nav2_pyif_planners.simple_smoother:SimpleSmoother"
    host = start_host("--key", SMOOTHER, "--planner", spec)
    client = connect(SmootherClient, zsession_factory, host, SMOOTHER)
    assert client.configure() == {
        "tolerance": 1e-10,
        "max_its": 1000,
        "w_data": 0.2,
        "w_smooth": 0.3,
        "do_refinement": True,
        "refinement_num": 2,
    }
    client.activate()
    smoothed = client.smooth(ZIGZAG, max_time=1.0)
    assert client.was_completed and smoothed.frame_id == "map" and len(smoothed) == 17
    np.testing.assert_allclose(smoothed.xy[[0, -1]], ZIGZAG.xy[[0, -1]])  # ends stay
    wiggle = np.abs(np.diff(ZIGZAG.xy[:, 1])).sum()
    assert np.abs(np.diff(smoothed.xy[:, 1])).sum() < 0.5 * wiggle
    # ros2 param set: a stiffer pull towards the data leaves more of the zigzag
    assert client.set_parameters({"w_data": 0.9}) == {}
    stiffer = client.smooth(ZIGZAG, max_time=1.0)
    assert np.abs(np.diff(stiffer.xy[:, 1])).sum() > np.abs(np.diff(smoothed.xy[:, 1])).sum()
    with pytest.raises(api.FailedToSmoothPath, match="empty"):
        client.smooth(Plan(np.zeros((0, 2)), "map"), max_time=1.0)
    client.deactivate()
    client.cleanup()


@pytest.mark.parametrize(
    ("fault", "error", "words"),
    [
        ("invalid_path", api.InvalidPath, "doubles back"),
        ("collision", api.SmoothedPathInCollision, "lethal"),
        ("failed", api.FailedToSmoothPath, "nothing to smooth"),
        ("nan", api.FailedToSmoothPath, "non-finite values in 3 of 3"),
        ("zero_division", api.SmootherException, "ZeroDivisionError"),
    ],
)
def test_smoother_errors_are_nav2s_smoother_exceptions(
    start_host: Any, zsession_factory: Any, fault: str, error: type, words: str
) -> None:
    host = start_host("--key", SMOOTHER, "--planner", "plugin_kinds:FaultySmoother")
    client = connect(SmootherClient, zsession_factory, host, SMOOTHER)
    client.configure()
    client.set_parameters({"fault": fault})
    with pytest.raises(error, match=words) as caught:
        client.smooth(ZIGZAG, max_time=1.0)
    assert isinstance(caught.value, api.SmootherException)  # never a controller's class
    client.set_parameters({"fault": "incomplete"})  # the next call works
    assert len(client.smooth(ZIGZAG, max_time=1.0)) == 17 and not client.was_completed


def test_a_smoother_key_refuses_another_plugin_kind(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", SMOOTHER, "--planner", "plugin_kinds:FaultySmoother")
    checker = connect(GoalCheckerClient, zsession_factory, host, SMOOTHER)
    with pytest.raises(api.ControllerException, match="a smoother"):
        checker.configure()


def test_stopped_goal_checker(start_host: Any, zsession_factory: Any) -> None:
    spec = "nav2_pyif_planners.checker_plugins:StoppedGoalChecker"
    host = start_host("--key", GOAL, "--planner", spec)
    client = connect(GoalCheckerClient, zsession_factory, host, GOAL)
    declared = client.configure()
    assert declared["xy_goal_tolerance"] == 0.25 and declared["stateful"] is True
    assert client.get_tolerances() == GoalTolerances(0.25, 0.25, 0.25, 0.25)
    goal = pose(2.0, 1.0)
    assert not client.is_goal_reached(pose(1.0, 1.0), goal, twist())  # 1 m away
    assert not client.is_goal_reached(pose(2.0, 1.0, 1.0), goal, twist())  # heading off
    assert client.is_goal_reached(pose(2.4, 1.0), goal, twist())  # position latched
    assert not client.is_goal_reached(pose(2.0, 1.0), goal, twist(vx=0.5))  # still moving
    client.reset()
    assert not client.is_goal_reached(pose(2.4, 1.0), goal, twist())  # latch forgotten
    assert client.set_parameters({"xy_goal_tolerance": 0.5}) == {}
    assert client.is_goal_reached(pose(2.4, 1.0), goal, twist())
    assert client.get_tolerances() == GoalTolerances(0.5, 0.25, 0.25, 0.25)


def test_simple_progress_checker_runs_on_the_poses_stamps(
    start_host: Any, zsession_factory: Any
) -> None:
    spec = "nav2_pyif_planners.checker_plugins:SimpleProgressChecker"
    host = start_host("--key", PROGRESS, "--planner", spec)
    client = connect(ProgressCheckerClient, zsession_factory, host, PROGRESS, costmap=no_costmap())
    assert client.configure() == {"required_movement_radius": 0.5, "movement_time_allowance": 10.0}
    assert client.check(stamped(0.0, 0.0, 100.0))  # the baseline
    assert client.check(stamped(0.2, 0.0, 109.0))  # not far, but within the allowance
    assert not client.check(stamped(0.3, 0.0, 110.5))  # 10.5 s without moving 0.5 m
    assert client.check(stamped(0.6, 0.0, 111.0))  # moved: a new baseline
    assert not client.check(stamped(0.6, 0.0, 121.5))
    client.reset()
    assert client.check(stamped(0.6, 0.0, 122.0))


def test_seed_style_functions_serve_a_goal_checker_and_a_smoother(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", GOAL, "--module", "seed_checkers")
    checker = connect(GoalCheckerClient, zsession_factory, host, GOAL)
    assert checker.configure() == {"xy_goal_tolerance": 0.3}
    assert checker.is_goal_reached(pose(1.0, 1.0), pose(1.2, 1.0), twist())
    assert not checker.is_goal_reached(pose(1.0, 1.0), pose(1.4, 1.0), twist())
    assert checker.get_tolerances() == GoalTolerances(0.3, math.pi, 0.1, 0.1)
    assert "reset has no delegate" in host.log()
    assert "activate has no delegate" not in host.log()  # Nav2's checkers have no activate
    host = start_host("--key", SMOOTHER, "--module", "seed_smoother")
    smoother = connect(SmootherClient, zsession_factory, host, SMOOTHER)
    smoother.configure()
    smoothed = smoother.smooth(ZIGZAG, max_time=1.0)
    np.testing.assert_allclose(smoothed.xy[1:-1, 1], 0.5 + 0.05 / 3 * (1 + np.arange(15) % 2))


def worker_pid(host: Any, key: str) -> int | None:
    return worker_pid_in(host.log(), key)


def test_a_killed_worker_is_restarted_with_the_sessions_state(
    start_host: Any, zsession_factory: Any
) -> None:
    """SIGKILL of the smoother's and the goal checker's workers between calls: the host
    replays each session's journal (configure, parameters) on a new worker; the plugins see
    no SessionUnknown."""
    host = start_host(
        "--key",
        SMOOTHER,
        "--planner",
        "plugin_kinds:FaultySmoother",
        "--serve",
        f"{GOAL}=nav2_pyif_planners.checker_plugins:StoppedGoalChecker",
    )
    smoother = connect(SmootherClient, zsession_factory, host, SMOOTHER)
    smoother.configure()
    smoother.activate()
    smoother.set_parameters({"shift": 3.0})
    checker = connect(GoalCheckerClient, zsession_factory, host, GOAL)
    checker.configure()
    checker.set_parameters({"xy_goal_tolerance": 0.75})
    for key in (SMOOTHER, GOAL):
        first = worker_pid(host, key)
        assert first is not None
        os.kill(first, signal.SIGKILL)
        assert wait_until(lambda k=key, f=first: worker_pid(host, k) not in (f, None), 30)
    time.sleep(0.2)
    shifted = smoother.smooth(ZIGZAG, max_time=1.0)
    np.testing.assert_allclose(shifted.xy[:, 1] - ZIGZAG.xy[:, 1], 3.0)
    assert checker.get_tolerances() == GoalTolerances(0.75, 0.25, 0.25, 0.25)
    assert smoother.resyncs == checker.resyncs == 0
    assert "restarted, 1 session(s) restored" in host.log()


def test_a_crash_during_smooth_is_unavailable_then_served_again(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", SMOOTHER, "--planner", "plugin_kinds:FaultySmoother")
    smoother = connect(SmootherClient, zsession_factory, host, SMOOTHER)
    smoother.configure()
    smoother.set_parameters({"fault": "crash"})
    with pytest.raises(api.SmootherException, match=r"\[Unavailable\].*exited with code 3"):
        smoother.smooth(ZIGZAG, max_time=1.0)


def test_hot_swap_of_a_smoother_carries_its_session(start_host: Any, zsession_factory: Any) -> None:
    host = start_host(
        "--key",
        SMOOTHER,
        "--planner",
        "plugin_kinds:FaultySmoother",
        "--allow-remote-reload",
        "--reload-allow",
        "plugin_kinds:*",
    )
    smoother = connect(SmootherClient, zsession_factory, host, SMOOTHER)
    smoother.configure()
    smoother.set_parameters({"shift": 0.5})
    message = request_reload(smoother.session, SMOOTHER, planner="plugin_kinds:ShiftBy2")
    assert "1 session(s) carried over" in message
    shifted = smoother.smooth(ZIGZAG, max_time=1.0)
    np.testing.assert_allclose(shifted.xy[:, 1] - ZIGZAG.xy[:, 1], 1.0)
    assert smoother.resyncs == 0
