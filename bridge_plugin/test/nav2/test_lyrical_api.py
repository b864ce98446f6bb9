"""What Lyrical's Nav2 gives Python plugins that earlier ones do not, in the real
controller_server and planner_server (planners/lyrical_reports.py reports each in the host's
log):

1. a Python controller follows the plan controller_server transformed for each cycle, with the
   global goal, and is never sent the same plan twice in a row; the goal checker's path
   length tolerance reaches it;
2. ComputePathToPose's viapoints reach a Python planner, whose plan passes through them;
3. Nav2's own RegulatedPurePursuit (testenv/build.sh builds it everywhere) asks the Python goal
   checker isGoalXYReached.

Lyrical only (nav2_core/path_handler.hpp): skipped, naming it, elsewhere
(tests/test_nav2_launch.py runs this file for the lyrical variants only).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

PREFIX = nav2_testing.PREFIX
GOAL = (2.0, 0.5)  # behind the wall
VIAPOINT = (1.0, -1.0)  # below the wall (x = 1, y from -0.6), clear of the robot's radius
RPP = nav2_testing.NATIVE_PURE_PURSUIT
PLANNERS = (
    *("--path", str(nav2_testing.HERE / "planners")),
    *("--serve", f"{PREFIX}/FollowPath=lyrical_reports:ReportingPursuit"),
    *("--serve", f"{PREFIX}/GridBased=lyrical_reports:ThroughViapoints"),
    *("--serve", f"{PREFIX}/general_goal_checker=lyrical_reports:ReportingGoalChecker"),
)
SUCCEEDED = nav2_testing.SUCCEEDED

pytestmark = pytest.mark.skipif(
    not nav2_testing.is_lyrical(),
    reason="Lyrical's API test skipped: this Nav2 has no nav2_core/path_handler.hpp "
    "(Humble, Jazzy, Kilted: controller_server has no path handler)",
)


def lyrical_plugins(text: str) -> str:
    """The Python goal checker as controller_server's only one; Nav2's RPP beside the Python
    controller."""
    lines = text.splitlines()
    follow = lines.index(f'      key: "{PREFIX}/FollowPath"')
    connect = lines[follow + 1].strip()
    start = lines.index("    general_goal_checker:")
    end = lines.index("    FollowPath:")
    checker = [
        "    general_goal_checker:",
        '      plugin: "nav2_pyif_bridge::PyGoalChecker"',
        f'      key: "{PREFIX}/general_goal_checker"',
        f"      {connect}",
        "      timeout: 0.5",
        "      wait_for_host: 20.0",
        "      xy_goal_tolerance: 0.25",
        "      yaw_goal_tolerance: 3.2",
        "      trans_stopped_velocity: 10.0",
        "      rot_stopped_velocity: 10.0",
    ]
    out = [*lines[:start], *checker, *lines[end:]]
    at = out.index('    controller_plugins: ["FollowPath"]')
    out[at] = '    controller_plugins: ["FollowPath", "NativeRPP"]'
    last = out.index(f'      key: "{PREFIX}/FollowPath"')
    while out[last + 1].startswith("      "):  # the end of FollowPath's section
        last += 1
    out[last + 1 : last + 1] = [
        "    NativeRPP:",
        f'      plugin: "{RPP}"',
        "      desired_linear_vel: 0.4",
        "      use_rotate_to_heading: true",
    ]
    return "\n".join(out)


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    yield from nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_lyrical_api"),
        planners=PLANNERS,
        edit_params=lyrical_plugins,
    )


def _reports(nav2: dict[str, Any], pattern: str) -> list[re.Match[str]]:
    path = nav2["logs"] / "planner_host.log"
    text = path.read_text(errors="replace") if path.exists() else ""
    return list(re.finditer(pattern, text))


def _active(nav2: dict[str, Any]) -> None:
    servers = ("controller_server", "planner_server")
    states = nav2["client"].wait_active(servers, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + "\n".join(
        nav2["procs"].log(n) for n in (*servers, "lifecycle_manager", "planner_host")
    )


def _follow(nav2: dict[str, Any], path: Any, controller: str = "FollowPath") -> None:
    client = nav2["client"]
    handle = client.wait(client.send_follow(path, controller=controller), 10.0)
    assert handle is not None and handle.accepted, "FollowPath not accepted"
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(nav2["procs"].log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    x, y = client.pose
    end = path.poses[-1].pose.position
    assert math.hypot(x - end.x, y - end.y) < 0.35, f"robot at {(x, y)}"


def test_the_controller_gets_the_transformed_plan_once_per_change_and_the_global_goal(
    nav2: dict[str, Any],
) -> None:
    _active(nav2)
    planned = nav2["client"].plan(*GOAL)
    assert planned is not None and planned.status == SUCCEEDED, nav2["procs"].log("planner_host")
    path = planned.result.path
    _follow(nav2, path)
    plans = _reports(
        nav2, r"report: plan of (\d+) poses, same as the last: (\w+), global goal (.*)"
    )
    assert len(plans) > 3, [m.group(0) for m in plans]  # pruned as the robot went: new plans
    assert all(m.group(2) == "False" for m in plans), "a plan sent again unchanged"
    assert all(int(m.group(1)) < len(path.poses) for m in plans[1:])  # parts, not the plan
    end = path.poses[-1].pose.position
    assert {m.group(3) for m in plans} == {f"({end.x:.3f}, {end.y:.3f})"}  # odom = map here
    tolerance = _reports(nav2, r"report: path_length_tolerance=(\S+)")
    assert tolerance and float(tolerance[0].group(1)) == 1.5, [m.group(0) for m in tolerance]


def test_viapoints_reach_the_python_planner(nav2: dict[str, Any]) -> None:
    _active(nav2)
    planned = nav2["client"].plan(*GOAL, viapoints=[VIAPOINT])
    assert planned is not None and planned.status == SUCCEEDED, nav2["procs"].log("planner_host")
    said = _reports(nav2, r"report: (\d+) viapoints: (.*)")
    assert said and said[-1].group(1) == "1", [m.group(0) for m in said]
    xy = [(p.pose.position.x, p.pose.position.y) for p in planned.result.path.poses]
    assert min(math.dist(p, VIAPOINT) for p in xy) < 0.05, "the plan misses the viapoint"


def test_nav2s_own_controller_asks_the_python_goal_checker_is_goal_xy_reached(
    nav2: dict[str, Any],
) -> None:
    _active(nav2)
    planned = nav2["client"].plan(0.0, 0.0)
    assert planned is not None and planned.status == SUCCEEDED, nav2["procs"].log("planner_host")
    _follow(nav2, planned.result.path, controller="NativeRPP")
    assert _reports(nav2, r"report: is_goal_xy_reached asked"), nav2["procs"].log("planner_host")
