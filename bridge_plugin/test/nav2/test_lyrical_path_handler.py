"""Lyrical's nav2_core::PathHandler served from Python, in the real controller_server: its only
path handler is a PyPathHandler answered by the reference PruningPathHandler (Nav2's
FeasiblePathHandler rule), beside the Python controller, in one planner host:

1. FollowPath reaches the goal, the controller following the pruned part of the plan:
   controller_server's transformed_global_plan (what the path handler's segment became) starts
   by the robot and is about prune_distance long, never the whole plan; the path handler is
   asked every cycle;
2. the host is killed (SIGKILL) mid-goal: FollowPath aborts within a few timeouts, as with the
   controller alone, and controller_server stays active; a new host serves the next goal.

Lyrical only (nav2_core/path_handler.hpp): skipped, naming it, elsewhere
(tests/test_nav2_launch.py runs this file for the lyrical variants only).
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
GOAL = (2.0, 0.5)  # behind the wall
START = (0.0, 0.0)  # back again: the goals after the first start away from the robot
PRUNE_DISTANCE = 1.0  # [m]
PLANNERS = (
    *nav2_testing.REFERENCE_PLANNERS,
    *("--serve", f"{PREFIX}/path_handler=nav2_pyif_planners.path_handler:PruningPathHandler"),
)
SUCCEEDED, ABORTED = nav2_testing.SUCCEEDED, nav2_testing.ABORTED

pytestmark = pytest.mark.skipif(
    not nav2_testing.is_lyrical(),
    reason="Lyrical's path handler test skipped: this Nav2 has no nav2_core/path_handler.hpp "
    "(Humble, Jazzy, Kilted: controller_server has no path handler)",
)


def python_path_handler(text: str) -> str:
    """The test's params with a PyPathHandler as controller_server's only path handler,
    connected as the controller is (zenoh_connect, or zenoh_config on zenoh-c)."""
    lines = text.splitlines()
    follow = lines.index(f'      key: "{PREFIX}/FollowPath"')
    connect = lines[follow + 1].strip()
    at = lines.index('    controller_plugins: ["FollowPath"]')
    handler = [
        '    path_handler_plugins: ["path_handler"]',
        "    path_handler:",
        '      plugin: "nav2_pyif_bridge::PyPathHandler"',
        f'      key: "{PREFIX}/path_handler"',
        f"      {connect}",
        "      timeout: 0.5",
        "      wait_for_host: 20.0",
        f"      prune_distance: {PRUNE_DISTANCE}",
    ]
    return "\n".join([*lines[: at + 1], *handler, *lines[at + 1 :]])


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    yield from nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_path_handler"),
        planners=PLANNERS,
        edit_params=python_path_handler,
    )


def _logs(nav2: dict[str, Any], *names: str) -> str:
    return "\n".join(nav2["procs"].log(n) for n in names)


def _plan(nav2: dict[str, Any], goal: tuple[float, float] = GOAL, timeout: float = 60.0) -> Any:
    """A* to ``goal`` through the planner server; retried while the plugin waits for a new
    host."""
    client = nav2["client"]
    deadline = time.monotonic() + timeout
    planned = None
    while time.monotonic() < deadline:
        planned = client.plan(*goal)
        if planned is not None and planned.status == SUCCEEDED:
            return planned.result.path
        client.spin_until(lambda: False, 1.0)
    raise AssertionError(f"planning failed: {planned}\n" + _logs(nav2, "planner_server"))


def _length(path: Any) -> float:
    xy = [(p.pose.position.x, p.pose.position.y) for p in path.poses]
    return sum(math.dist(a, b) for a, b in itertools.pairwise(xy))


def test_a_python_path_handler_prunes_the_plan_and_survives_its_host(
    nav2: dict[str, Any],
) -> None:
    from nav_msgs.msg import Path

    client, procs = nav2["client"], nav2["procs"]
    servers = ("controller_server", "planner_server")
    states = client.wait_active(servers, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + _logs(
        nav2, *servers, "lifecycle_manager", "planner_host"
    )
    assert "path_handler.prune_distance" in client.list_parameters(
        "controller_server", "path_handler"
    )  # declared by the Python path handler

    # 1. FollowPath to the goal on the segments the Python path handler cut
    segments: list[tuple[tuple[float, float], tuple[float, float] | None, int, float]] = []

    def on_segment(msg: Any) -> None:
        first = msg.poses[0].pose.position if msg.poses else None
        segments.append(
            (
                client.pose or (math.nan, math.nan),
                (first.x, first.y) if first else None,
                len(msg.poses),
                _length(msg),
            )
        )

    watch = client.create_subscription(Path, "transformed_global_plan", on_segment, 10)
    plan = _plan(nav2)
    before = nav2_testing.host_queries(nav2["endpoint"])
    handle = client.follow(plan)
    result = client.wait(handle.get_result_async(), 90.0)
    client.destroy_subscription(watch)
    logs = _logs(nav2, "controller_server", "planner_host")
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}"
    assert len(segments) > 20, segments  # controller_server publishes each cycle's
    whole = _length(plan)
    for robot, first, count, length in segments:
        assert first is not None and count < len(plan.poses), (robot, first, count)
        assert length <= PRUNE_DISTANCE + 0.1 < whole, (length, whole)
    # the first pose of the segment is the plan's closest to the robot (odom = map here)
    near = [math.dist(robot, first) for robot, first, _, _ in segments if first]
    assert sorted(near)[len(near) // 2] < 0.3, near
    after = nav2_testing.host_queries(nav2["endpoint"])
    sent = {key.rsplit("/", 1)[1]: after[key] - before.get(key, 0) for key in after}
    # a segment a cycle, on its own query (the checks are Nav2's here) beside the command's
    assert sent["path_handler"] >= len(segments) // 2, (sent, len(segments))
    print(f"queries during FollowPath: {sent}, {len(segments)} transformed plans published")

    # 2. the host dies mid-goal (back to the start, from the goal): a clean abort,
    # controller_server stays up
    handle = client.follow(_plan(nav2, START))
    client.spin_until(lambda: False, 1.5)  # driving
    procs.kill("planner_host", signal.SIGKILL)
    killed = time.monotonic()
    result = client.wait(handle.get_result_async(), 30.0)
    logs = _logs(nav2, "controller_server")
    assert result is not None and result.status == ABORTED, f"FollowPath: {result}\n{logs}"
    assert time.monotonic() - killed < 5.0, "the abort took longer than a few timeouts"
    assert client.wait_active(servers, 10.0) == dict.fromkeys(servers, "active")

    # a new host serves the path handler and the controller again
    started = nav2["start_host"]()
    alive = f"is alive on {PREFIX}/path_handler"
    assert client.spin_until(lambda: procs.logged_at("controller_server", alive, started), 30.0), (
        procs.log("controller_server")
    )
    handle = client.follow(_plan(nav2, START))
    result = client.wait(handle.get_result_async(), 90.0)
    logs = _logs(nav2, "controller_server", "planner_host")
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
