"""Sensor inputs and debug outputs in the real Nav2: the simulated robot
publishes /scan; the Python controller (planners/scan_guard.py) gets each new scan through the
plugin's `inputs` parameter and will not drive without one; it returns the nearest return
ahead and its local plan as debug outputs, which the plugin publishes on FollowPath/... while
someone subscribes.

Needs what test_nav2_pyif.py needs.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

GOAL = (2.0, 0.5)  # behind the sim's wall (x = 1 m, y from -0.6 to 2.5 m): the scan sees it
SCAN_INPUT = """      inputs: ["scan"]
      scan:
        topic: /scan
        type: sensor_msgs/msg/LaserScan
"""


def _with_scan_input(params: str) -> str:
    anchor = '      key: "nav2_pyif/launch_test/FollowPath"\n'
    assert anchor in params
    return params.replace(anchor, anchor + SCAN_INPUT)


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    planners = (
        *("--path", str(nav2_testing.HERE / "planners")),
        *("--serve", f"{nav2_testing.PREFIX}/FollowPath=scan_guard:ScanGuard"),
        *("--serve", f"{nav2_testing.PREFIX}/GridBased=nav2_pyif_planners.astar:AStar"),
    )
    yield from nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_sensor_inputs"),
        robot_args=("--scan",),
        planners=planners,
        edit_params=_with_scan_input,
    )


def test_a_scan_reaches_the_python_controller_and_its_debug_topics_are_published(
    nav2: dict[str, Any],
) -> None:
    from geometry_msgs.msg import PointStamped
    from nav_msgs.msg import Path

    client, procs = nav2["client"], nav2["procs"]
    returns: list[PointStamped] = []
    local_plans: list[Path] = []
    client.create_subscription(PointStamped, "FollowPath/nearest_return", returns.append, 10)
    client.create_subscription(Path, "FollowPath/local_plan", local_plans.append, 10)
    states = client.wait_active(nav2_testing.SERVERS, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + procs.log("planner_host")
    log = procs.log("controller_server", 200)
    assert "input 'scan' from /scan (sensor_msgs/msg/LaserScan)" in log, log
    assert "debug output on FollowPath/nearest_return" in log, log

    planned = client.plan(*GOAL)
    assert planned is not None and planned.status == nav2_testing.SUCCEEDED, procs.log(
        "planner_server"
    )
    handle = client.follow(planned.result.path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host", "sim_robot"))
    # ScanGuard raises NoValidControl without a scan: reaching the goal needs the scans
    assert result is not None and result.status == nav2_testing.SUCCEEDED, f"{result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL}"
    assert client.spin_until(lambda: len(returns) > 5 and len(local_plans) > 5, 5.0), logs
    # the nearest returns lie on the wall's near face, in the local costmap's frame (odom)
    on_wall = [p for p in returns if abs(p.point.x - 1.0) < 0.1 and -0.7 <= p.point.y <= 2.6]
    assert len(on_wall) > 0.9 * len(returns), [(p.point.x, p.point.y) for p in returns[:10]]
    assert {p.header.frame_id for p in returns} == {"odom"}
    assert all(len(p.poses) > 1 and p.header.frame_id == "odom" for p in local_plans)
