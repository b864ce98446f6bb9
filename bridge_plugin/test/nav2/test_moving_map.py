"""A plan that stays fresh: the simulated robot's odometry drifts, and map -> odom
jumps 10 cm at a time (40 cm in all) while the robot drives, as AMCL's corrections do. The
plugin transformed the plan into the local costmap's frame (odom) at setPlan; it re-sends it,
transformed anew, when that transform moves. The robot reaches the goal in the map frame.
Without the re-send it follows a plan 40 cm off and never gets within the goal tolerance.

Needs what test_nav2_pyif.py needs; skipped, saying what is missing, otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_testing
import pytest

GOAL = (-2.5, 0.0)  # straight along -x; the drift is along y


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    logs: Path = tmp_path_factory.mktemp("nav2_moving_map")
    drift = ("--drift-step", "0.1", "--drift-period", "1.0", "--drift-max", "0.4")
    yield from nav2_testing.bring_up(logs, drift)


def test_the_robot_reaches_the_goal_while_map_to_odom_moves(nav2: dict[str, Any]) -> None:
    from geometry_msgs.msg import PoseStamped

    client, procs = nav2["client"], nav2["procs"]
    truth: list[tuple[float, float]] = []
    client.create_subscription(
        PoseStamped,
        "ground_truth",
        lambda m: truth.append((m.pose.position.x, m.pose.position.y)),
        10,
    )
    states = client.wait_active(nav2_testing.SERVERS, 90.0)
    assert all(s == "active" for s in states.values()), states
    planned = client.plan(*GOAL)
    assert planned is not None and planned.status == nav2_testing.SUCCEEDED, procs.log(
        "planner_server"
    )
    handle = client.follow(planned.result.path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host", "sim_robot"))
    assert result is not None and result.status == nav2_testing.SUCCEEDED, f"{result}\n{logs}"
    assert client.spin_until(lambda: bool(truth), 5.0)
    x, y = truth[-1]
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.3, f"robot at {(x, y)} in the map, goal {GOAL}"
    # the odom frame did move under the plan: odometry ends 30-40 cm from the truth
    assert client.pose is not None and y - client.pose[1] > 0.29, (client.pose, y)
