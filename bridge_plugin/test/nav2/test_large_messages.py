"""Messages of any size through the real Nav2 on each zenoh-cpp backend: a 50 m map
at 5 cm, so the global costmap the planner gets is 1000 x 1000 cells (1 MB in the request),
and a planner whose every plan has 10 000 poses (0.56 MB in its reply, and again in the
controller's setPlan). The plan arrives whole in ComputePathToPose, and FollowPath drives it
to the goal.

Needs what test_nav2_pyif.py needs.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record

CELLS, POSES = 1000, 10_000
GOAL = (2.0, 0.5)  # behind the sim's wall


def _dense_planner(params: str) -> str:
    """GridBased's Python parameters: the costmap size it must see, the poses to return."""
    anchor = "      allow_unknown: true\n"
    assert anchor in params
    return params.replace(anchor, f"{anchor}      expected_cells: {CELLS}\n      poses: {POSES}\n")


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    planners = (
        *("--path", str(nav2_testing.HERE / "planners")),
        *(
            "--serve",
            f"{nav2_testing.PREFIX}/FollowPath=nav2_pyif_planners.pure_pursuit:"
            "RegulatedPurePursuit",
        ),
        *("--serve", f"{nav2_testing.PREFIX}/GridBased=dense_planner:DensePlanner"),
    )
    yield from nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_large_messages"),
        robot_args=("--map-size", str(CELLS * 0.05)),
        planners=planners,
        edit_params=_dense_planner,
    )


def test_a_1000x1000_costmap_and_10000_pose_plans_cross_whole(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    states = client.wait_active(nav2_testing.SERVERS, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + procs.log("planner_host")

    asked = time.monotonic()
    planned = client.plan(*GOAL, timeout=60.0)
    took = time.monotonic() - asked
    logs = "\n".join(procs.log(n) for n in ("planner_server", "planner_host"))
    assert planned is not None and planned.status == nav2_testing.SUCCEEDED, logs
    path = planned.result.path
    assert len(path.poses) == POSES, f"{len(path.poses)} poses\n{logs}"
    end = path.poses[-1].pose.position
    assert math.hypot(end.x - GOAL[0], end.y - GOAL[1]) < 0.05, (end.x, end.y)

    handle = client.follow(path)
    result = client.wait(handle.get_result_async(), 120.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == nav2_testing.SUCCEEDED, f"{result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL}"
    record(large_first_plan_1000x1000_costmap_10000_poses_s=took)
