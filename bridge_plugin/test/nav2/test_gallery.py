"""The examples/ gallery in the real Nav2: planner_server's PyGlobalPlanner plans with the OMPL
example (examples/ompl_planner: RRT*, its threshold circumscribed_cost() from the inflation
layer Nav2's plugin reports) and controller_server's PyController follows the plan with the
DWA example (examples/dwa, its window from controller_frequency), both served by one planner
host with ``--path examples`` as a user serves their own modules: the robot reaches a goal
behind the wall.

Needs what test_nav2_pyif.py needs, and OMPL in the planner host's environment
(``python -m pip install '.[ompl]'`` in the clone; tests/test_nav2_launch.py checks it).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

GOAL = (2.0, 0.5)  # behind the sim's wall (x = 1 m, y from -0.6 to 2.5 m)
EXAMPLES = nav2_testing.HERE.parents[2] / "examples"


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    planners = (
        *("--path", str(EXAMPLES)),
        *("--serve", f"{nav2_testing.PREFIX}/FollowPath=dwa.controller:DWA"),
        *("--serve", f"{nav2_testing.PREFIX}/GridBased=ompl_planner.planner:OMPLPlanner"),
    )
    yield from nav2_testing.bring_up(tmp_path_factory.mktemp("nav2_gallery"), planners=planners)


def test_ompl_plans_and_dwa_drives_to_the_goal(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    states = client.wait_active(nav2_testing.SERVERS, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + procs.log("planner_host")
    planned = client.plan(*GOAL)
    logs = "\n".join(procs.log(n) for n in ("planner_server", "planner_host"))
    assert planned is not None and planned.status == nav2_testing.SUCCEEDED, logs
    path = planned.result.path
    assert len(path.poses) > 10 and path.header.frame_id == "map", logs
    ends = path.poses[0].pose.position, path.poses[-1].pose.position
    assert math.hypot(ends[1].x - GOAL[0], ends[1].y - GOAL[1]) < 0.05, ends
    # around the wall, not through it: every pose whose x is on the wall's line is past its end
    crossing = [p.pose.position for p in path.poses if abs(p.pose.position.x - 1.0) < 0.1]
    assert all(not -0.6 <= p.y <= 2.5 for p in crossing), [(p.x, p.y) for p in crossing]

    handle = client.follow(path)
    result = client.wait(handle.get_result_async(), 120.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host", "sim_robot"))
    assert result is not None and result.status == nav2_testing.SUCCEEDED, f"{result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL}"
    host_log = procs.log("planner_host", 400)
    for served in ("ompl_planner.planner:OMPLPlanner", "dwa.controller:DWA"):
        assert f"serving {served}" in host_log, host_log
