"""Other plugin types in the real Nav2: smoother_server with the Python smoother (PySmoother), and
controller_server whose only goal checker and progress checker are Python ones
(PyGoalChecker, PyProgressChecker), all served by one planner host:

1. SmoothPath returns the A* plan smoothed (same ends, straighter) by the Python
   SimpleSmoother;
2. FollowPath ends when the Python goal checker says so (it is controller_server's only one);
   `ros2 param set` on the Python progress checker makes the next FollowPath abort with
   FAILED_TO_MAKE_PROGRESS;
3. the host is killed (SIGKILL) mid-goal: FollowPath and SmoothPath fail cleanly, the servers
   stay active; a new host serves both again.
"""

from __future__ import annotations

import itertools
import math
import signal
import time
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

PREFIX = nav2_testing.PREFIX
GOAL_A = (2.0, 0.5)  # behind the wall
GOAL_B = (0.0, 0.0)
SERVERS = ("controller_server", "planner_server", "smoother_server")
CHECKERS = "nav2_pyif_planners.checker_plugins"
PLANNERS = (
    *nav2_testing.REFERENCE_PLANNERS,
    *("--serve", f"{PREFIX}/simple_smoother=nav2_pyif_planners.simple_smoother:SimpleSmoother"),
    *("--serve", f"{PREFIX}/general_goal_checker={CHECKERS}:StoppedGoalChecker"),
    *("--serve", f"{PREFIX}/progress_checker={CHECKERS}:SimpleProgressChecker"),
)
SUCCEEDED, ABORTED = nav2_testing.SUCCEEDED, nav2_testing.ABORTED


def python_checkers_and_smoother(text: str) -> str:
    """The test's params with the Python checkers and a smoother_server with PySmoother,
    connected as the controller is (zenoh_connect, or zenoh_config on zenoh-c)."""
    lines = text.splitlines()
    follow = lines.index(f'      key: "{PREFIX}/FollowPath"')
    connect = lines[follow + 1].strip()  # the plugins' Zenoh connection, as the YAML has it
    start = lines.index("    progress_checker:")
    end = lines.index("    FollowPath:")
    checkers = f"""    progress_checker:
      plugin: "nav2_pyif_bridge::PyProgressChecker"
      key: "{PREFIX}/progress_checker"
      {connect}
      timeout: 0.5
      wait_for_host: 20.0
      required_movement_radius: 0.3
      movement_time_allowance: 15.0
    general_goal_checker:
      plugin: "nav2_pyif_bridge::PyGoalChecker"
      key: "{PREFIX}/general_goal_checker"
      {connect}
      timeout: 0.5
      wait_for_host: 20.0
      xy_goal_tolerance: 0.25
      yaw_goal_tolerance: 3.2
      trans_stopped_velocity: 10.0  # the pure pursuit stops at the goal; any speed will do
      rot_stopped_velocity: 10.0"""
    smoother = f"""smoother_server:
  ros__parameters:
    use_sim_time: false
    costmap_topic: global_costmap/costmap_raw
    footprint_topic: global_costmap/published_footprint
    smoother_plugins: ["simple_smoother"]
    simple_smoother:
      plugin: "nav2_pyif_bridge::PySmoother"
      key: "{PREFIX}/simple_smoother"
      {connect}
      wait_for_host: 20.0
      w_smooth: 0.3"""
    out = "\n".join([*lines[:start], checkers, *lines[end:]])
    out = out.replace(
        'node_names: ["controller_server", "planner_server"]',
        'node_names: ["controller_server", "planner_server", "smoother_server"]',
    )
    manager = "lifecycle_manager_navigation:"
    return out.replace(manager, f"{smoother}\n{manager}")


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    yield from nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_smoother_checkers"),
        planners=PLANNERS,
        edit_params=python_checkers_and_smoother,
        servers=SERVERS,
    )


def _logs(nav2: dict[str, Any], *names: str) -> str:
    return "\n".join(nav2["procs"].log(n) for n in names)


def _plan(nav2: dict[str, Any], goal: tuple[float, float], timeout: float = 60.0) -> Any:
    """A* through the planner server; retried while the plugin waits for a new host."""
    client = nav2["client"]
    deadline = time.monotonic() + timeout
    planned = None
    while time.monotonic() < deadline:
        planned = client.plan(*goal)
        if planned is not None and planned.status == SUCCEEDED:
            return planned.result.path
        client.spin_until(lambda: False, 1.0)
    raise AssertionError(f"planning failed: {planned}\n" + _logs(nav2, "planner_server"))


def _turning(path: Any) -> float:
    """Summed heading change along the path's points [rad]: less when smoother."""
    xy = [(p.pose.position.x, p.pose.position.y) for p in path.poses]
    headings = [math.atan2(b[1] - a[1], b[0] - a[0]) for a, b in itertools.pairwise(xy) if a != b]
    return sum(
        abs(math.atan2(math.sin(b - a), math.cos(b - a))) for a, b in itertools.pairwise(headings)
    )


def test_python_smoother_and_checkers_in_nav2(nav2: dict[str, Any]) -> None:

    client, procs = nav2["client"], nav2["procs"]
    states = client.wait_active(SERVERS, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + _logs(
        nav2, *SERVERS, "lifecycle_manager", "planner_host"
    )

    # 1. SmoothPath: the Python SimpleSmoother's result
    raw = _plan(nav2, GOAL_A)
    smoothed = client.smooth(raw, "simple_smoother")
    assert smoothed is not None and smoothed.status == SUCCEEDED, (
        f"SmoothPath: {smoothed}\n" + _logs(nav2, "smoother_server", "planner_host")
    )
    path = smoothed.result.path
    assert smoothed.result.was_completed
    assert len(path.poses) == len(raw.poses) and path.header.frame_id == "map"
    for i in (0, -1):
        a, b = path.poses[i].pose.position, raw.poses[i].pose.position
        assert (a.x, a.y) == pytest.approx((b.x, b.y)), "the ends moved"
    assert _turning(path) < 0.8 * _turning(raw), (_turning(path), _turning(raw))
    names = client.list_parameters("smoother_server", "simple_smoother")
    assert "simple_smoother.refinement_num" in names  # declared by the Python smoother

    # 2. FollowPath ends by the Python goal checker, the only one controller_server has
    before = nav2_testing.host_queries(nav2["endpoint"])
    handle = client.follow(path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = _logs(nav2, "controller_server", "planner_host")
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL_A[0], y - GOAL_A[1]) < 0.35, f"robot at {(x, y)}"
    # A call's query carried the calls of the cycle after it (PROTOCOL.md section 15), in
    # the order this controller_server calls them. Goal check first: the goal check carries
    # the check and the command, about one query a cycle. The command goes on its own when
    # Nav2 calls it with another velocity than the goal check got (its odometry smoother moved
    # on between the two reads), or after set_plan; the check goes on its own at its reset and
    # in cycles where TF moved on between the goal check's pose lookup and the next one (1-50 %
    # of them here, as the sim's 50 Hz TF and the 20 Hz loop lock in phase: BENCHMARKS.md,
    # "Goal and progress checkers"), carrying the command: two queries; a fully locked phase
    # (50 %) costs 1.51 and fails this target. Goal check last: the check goes on its own
    # and the command carries the goal check, two queries; the goal check goes on its own too
    # when TF moved on between the command's pose lookup and its own, a window of two queries
    # (2.07 to 2.47 here, loaded); the same half of the cycles missing fails the target.
    # Lyrical: goal check first, but controller_server's own path handler prunes the plan
    # between the progress check and the command, and the command takes that segment; so the
    # goal check carries only the check, and the command goes on its own: two queries, 2.09
    # and 2.21 measured (testenv/README.md). The mechanism is tested call by call in
    # carried_test.cpp.
    after = nav2_testing.host_queries(nav2["endpoint"])
    sent = {key.rsplit("/", 1)[1]: after[key] - before.get(key, 0) for key in after}
    first = nav2_testing.goal_check_first()
    # Every cycle sends its goal check (goal first) or its progress check (goal last) alone.
    cycles = sent["general_goal_checker" if first else "progress_checker"]
    assert cycles > 40, sent  # 20 Hz for a few seconds
    queries = sum(sent[k] for k in ("general_goal_checker", "progress_checker", "FollowPath"))
    lyrical = nav2_testing.is_lyrical()
    assert queries < (1.5 if first and not lyrical else 2.5) * cycles, sent  # 3 uncarried
    order = "goal check first" if first else "goal check last"
    order += ", the command on Nav2's pruned segment" if lyrical else ""
    print(f"queries during FollowPath ({order}): {sent}, {queries / cycles:.2f} per control cycle")
    assert "general_goal_checker.stateful" in client.list_parameters(
        "controller_server", "general_goal_checker"
    )  # declared by the Python goal checker
    # the Python progress checker, made impatient with `ros2 param set`, stops the next goal
    for name, value in (("required_movement_radius", 50.0), ("movement_time_allowance", 0.5)):
        ok, reason = client.set_parameter("controller_server", f"progress_checker.{name}", value)
        assert ok, reason
    handle = client.follow(_plan(nav2, GOAL_B))
    result = client.wait(handle.get_result_async(), 30.0)
    logs = _logs(nav2, "controller_server", "planner_host")
    assert result is not None and result.status == ABORTED, f"FollowPath: {result}\n{logs}"
    nav2_testing.assert_error_code(result.result, "FAILED_TO_MAKE_PROGRESS", logs)
    for name, value in (("required_movement_radius", 0.3), ("movement_time_allowance", 15.0)):
        assert client.set_parameter("controller_server", f"progress_checker.{name}", value)[0]

    # 3. the host dies mid-goal: clean failures, Nav2 stays up
    handle = client.follow(_plan(nav2, GOAL_B))
    client.spin_until(lambda: False, 1.5)  # driving
    procs.kill("planner_host", signal.SIGKILL)
    killed = time.monotonic()
    result = client.wait(handle.get_result_async(), 30.0)
    logs = _logs(nav2, "controller_server")
    assert result is not None and result.status == ABORTED, f"FollowPath: {result}\n{logs}"
    assert time.monotonic() - killed < 5.0, "the abort took longer than a few timeouts"
    failed = client.smooth(raw, "simple_smoother")
    assert failed is not None and failed.status == ABORTED, _logs(nav2, "smoother_server")
    # no reply in time while the dead host's token lingers, or no host alive: SmootherException
    nav2_testing.assert_error_code(failed.result, "UNKNOWN")
    assert client.wait_active(SERVERS, 10.0) == dict.fromkeys(SERVERS, "active")

    # a new host: the smoother, the checkers and the controller are served again
    started = nav2["start_host"]()
    alive = f"is alive on {PREFIX}/general_goal_checker"
    assert client.spin_until(lambda: procs.logged_at("controller_server", alive, started), 30.0), (
        procs.log("controller_server")
    )
    path = _plan(nav2, GOAL_B)
    deadline = time.monotonic() + 30.0
    smoothed = None
    while time.monotonic() < deadline:  # until the smoother's plugin sees the new host
        smoothed = client.smooth(path, "simple_smoother")
        if smoothed is not None and smoothed.status == SUCCEEDED:
            break
        client.spin_until(lambda: False, 1.0)
    assert smoothed is not None and smoothed.status == SUCCEEDED, _logs(nav2, "smoother_server")
    handle = client.follow(smoothed.result.path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = _logs(nav2, "controller_server", "planner_host")
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL_B[0], y - GOAL_B[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL_B}"
