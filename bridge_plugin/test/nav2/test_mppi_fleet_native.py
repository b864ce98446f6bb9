"""Nav2's own MPPI for N robots on one machine, as a fleet runs it without nav2_pyif: a stack
per robot (controller_server with nav2_mppi_controller, planner_server with NavFn, a lifecycle
manager and the simulated robot), each in a ROS domain of its own, all following their plans
at once. The C++ side of the fleet comparison (BENCHMARKS.md, `nav2-pyif-bench mppi-fleet`):
per robot count, the controller_servers' CPU per robot-cycle, Nav2's MPPI's own compute per
cycle (its "Control loop execution time" lines, one per cycle with testenv's patch) and the
control periods missed (controller_server's "Control loop missed its desired rate", one per
period it overran).

A benchmark, not a test of the project's behaviour: it runs only when tests/test_nav2_launch.py
is asked for it (NAV2_PYIF_MPPI_FLEET_NATIVE=1), and skips, naming it, where
nav2_mppi_controller is not built (testenv/build.sh jazzy mppi). $NAV2_PYIF_MPPI_FLEET_ROBOTS:
the robot counts (default "1 5 10"); $NAV2_PYIF_MPPI_ROLLOUTS: the batch size (its first
count, default 1000). The same MPPI block as test_mppi_side_by_side.py. Figures go to
$NAV2_PYIF_FIGURES (JSON), printed by tests/test_nav2_launch.py.
"""

from __future__ import annotations

import os
import random
import statistics
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record
from test_mppi_side_by_side import NATIVE, _computes, _cpu_seconds, _params, _percentile

ROBOTS = [int(n) for n in os.environ.get("NAV2_PYIF_MPPI_FLEET_ROBOTS", "1 5 10").split()]
ROLLOUTS = int(os.environ.get("NAV2_PYIF_MPPI_ROLLOUTS", "1000").split()[0])
GOAL = (2.0, 0.5)  # around the simulated robot's wall, the side-by-side's first goal
EXECUTION = "Control loop execution time"
MISSED = "Control loop missed its desired rate"
pytestmark = pytest.mark.timeout(300 + 240 * sum(ROBOTS) // 5 + 120 * len(ROBOTS))


@dataclass
class Robot:
    procs: nav2_testing.Processes
    client: Any = None


@contextmanager
def _fleet(logs: Path, count: int) -> Iterator[list[Robot]]:
    """``count`` native MPPI stacks, each in a ROS domain of its own with an rclpy client
    there; every process stopped afterwards."""
    import rclpy

    robots: list[Robot] = []
    try:
        for i, domain in enumerate(random.sample(range(100, 200), count)):
            own = logs / f"robot{i}"
            own.mkdir()
            _, params, procs = nav2_testing.prepare(own, domain=domain)
            robots.append(Robot(procs))
            params.write_text(_params(params.read_text(), ROLLOUTS, native=True))
            procs.start("sim_robot", ["python3", str(nav2_testing.HERE / "sim_robot.py")])
            nav2_testing.start_nav2(procs, params)
            context = rclpy.Context()
            rclpy.init(context=context, domain_id=domain)
            robots[-1].client = nav2_testing.Nav2Client(context, f"nav2_pyif_fleet_{i}")
        yield robots
    finally:
        for robot in robots:
            if robot.client is None:
                robot.procs.stop_all()
            else:
                nav2_testing.tear_down(robot.client, robot.procs)


def _log(robot: Robot) -> str:
    path = robot.procs.logs / "controller_server.log"
    return path.read_text(errors="replace") if path.exists() else ""


def _drive_all(robots: list[Robot]) -> float:
    """Every robot planned to GOAL (NavFn), then all FollowPath goals sent at once and
    waited for; the seconds until the last one ended."""
    paths = []
    for robot in robots:
        planned = robot.client.plan(*GOAL)
        assert planned is not None and len(planned.result.path.poses) > 1, "no plan"
        paths.append(planned.result.path)
    sent = [robot.client.send_follow(path) for robot, path in zip(robots, paths, strict=True)]
    results = []
    for robot, future in zip(robots, sent, strict=True):
        handle = robot.client.wait(future, 10.0)
        assert handle is not None and handle.accepted, "FollowPath not accepted"
        results.append(handle.get_result_async())
    started = time.monotonic()
    while not all(r.done() for r in results) and time.monotonic() - started < 180.0:
        for robot, result in zip(robots, results, strict=True):
            robot.client.spin_until(result.done, 0.02)
    statuses = [r.result().status if r.done() else None for r in results]
    assert all(s == nav2_testing.SUCCEEDED for s in statuses), statuses
    return time.monotonic() - started


@pytest.mark.parametrize("count", ROBOTS)
def test_nav2s_mppi_for_a_fleet(count: int, tmp_path_factory: pytest.TempPathFactory) -> None:
    if nav2_testing.find("share/nav2_mppi_controller/package.xml") is None:
        pytest.skip("the native fleet needs nav2_mppi_controller: testenv/build.sh jazzy mppi")
    absent = nav2_testing.missing()
    if absent:
        pytest.skip("the Nav2 launch test needs: " + ", ".join(absent))
    with _fleet(tmp_path_factory.mktemp(f"mppi_fleet_native_{count}"), count) as robots:
        for robot in robots:
            states = robot.client.wait_active(nav2_testing.SERVERS, 120.0 + 30.0 * count)
            assert all(s == "active" for s in states.values()), states
            assert NATIVE in _log(robot), _log(robot)[-3000:]
        before = [_log(robot) for robot in robots]
        servers = [robot.procs.procs["controller_server"].pid for robot in robots]
        sims = [robot.procs.procs["sim_robot"].pid for robot in robots]
        cpu, sim_cpu = _cpu_seconds(servers), _cpu_seconds(sims)
        seconds = _drive_all(robots)
        cpu, sim_cpu = _cpu_seconds(servers) - cpu, _cpu_seconds(sims) - sim_cpu
        during = [_log(robot)[len(text) :] for robot, text in zip(robots, before, strict=True)]
    cycles = sum(text.count(EXECUTION) for text in during)
    missed = sum(text.count(MISSED) for text in during)
    computes = [ms for text in during for ms in _computes(text, native=True)]
    assert cycles > 0 and computes, f"no {EXECUTION!r} lines: is testenv's patch applied?"
    name = f"mppi_fleet_native_{ROLLOUTS}_{count}"
    figures: dict[str, float | int] = {
        f"{name}_cycles": cycles,
        f"{name}_missed": missed,
        f"{name}_cpu_per_robot_cycle_ms": 1e3 * cpu / cycles,
        f"{name}_compute_median_ms": statistics.median(computes),
        f"{name}_compute_p99_ms": _percentile(computes, 0.99),
        f"{name}_sim_cpu_share": sim_cpu / (seconds * (os.cpu_count() or 1)),
        f"{name}_seconds": seconds,
    }
    record(**figures)
    print(name, figures)
