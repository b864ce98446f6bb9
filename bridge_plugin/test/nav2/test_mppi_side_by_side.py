"""Nav2's own MPPI and the project's, side by side in the real controller_server: the same
Nav2 MPPI parameter block (nav2_bringup's Jazzy FollowPath, visualisation off), the same
simulated robot, plans and goals (around the wall and back), one stack per controller and
rollout count, in one session. A benchmark, not a test of the project's behaviour: it runs
only when tests/test_nav2_launch.py is asked for it (NAV2_PYIF_MPPI_SIDE_BY_SIDE=1), and
skips, naming it, where nav2_mppi_controller is not built (testenv/build.sh jazzy mppi).

Per controller: compute per cycle (Nav2's MPPI: its own "Control loop execution time" log
lines, whole ms; ours: the controller method alone, planners/timed_mppi.py), CPU of the
processes doing the work per cycle (controller_server; or the planner host and its workers),
the gaps between cmd_vel messages, FollowPath's time to the goal and the path driven.
$NAV2_PYIF_MPPI_RUNS round trips each (default 3); $NAV2_PYIF_MPPI_ROLLOUTS the rollout counts
(default "1000 2000"); $NAV2_PYIF_MPPI_OURS the served classes (module:Class, default the
timed JAX MPPI). Figures go to $NAV2_PYIF_FIGURES (JSON), printed by tests/test_nav2_launch.py.
"""

from __future__ import annotations

import itertools
import math
import os
import re
import statistics
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record

RUNS = int(os.environ.get("NAV2_PYIF_MPPI_RUNS", "3"))
ROLLOUTS = [int(n) for n in os.environ.get("NAV2_PYIF_MPPI_ROLLOUTS", "1000 2000").split()]
OURS = os.environ.get("NAV2_PYIF_MPPI_OURS", "timed_mppi:TimedMPPIJax").split()
GOALS = ((2.0, 0.5), (0.0, 0.0))
pytestmark = pytest.mark.timeout(300 + 120 * RUNS)
NATIVE = "nav2_mppi_controller::MPPIController"

# nav2_bringup's Jazzy FollowPath block (nav2_params.yaml), visualize off: what a Nav2 user's
# YAML holds. @PLUGIN@ is the controller; the rest is the same for both.
MPPI_BLOCK = """    FollowPath:
@PLUGIN@
      time_steps: 56
      model_dt: 0.05
      batch_size: @ROLLOUTS@
      ax_max: 3.0
      ax_min: -3.0
      ay_max: 3.0
      ay_min: -3.0
      az_max: 3.5
      vx_std: 0.2
      vy_std: 0.2
      wz_std: 0.4
      vx_max: 0.5
      vx_min: -0.35
      vy_max: 0.5
      wz_max: 1.9
      iteration_count: 1
      prune_distance: 1.7
      transform_tolerance: 0.1
      temperature: 0.3
      gamma: 0.015
      motion_model: "DiffDrive"
      visualize: false
      regenerate_noises: true
      critics: ["ConstraintCritic", "CostCritic", "GoalCritic", "GoalAngleCritic",
                "PathAlignCritic", "PathFollowCritic", "PathAngleCritic", "PreferForwardCritic"]
      ConstraintCritic: {enabled: true, cost_power: 1, cost_weight: 4.0}
      GoalCritic: {enabled: true, cost_power: 1, cost_weight: 5.0, threshold_to_consider: 1.4}
      GoalAngleCritic:
        {enabled: true, cost_power: 1, cost_weight: 3.0, threshold_to_consider: 0.5}
      PreferForwardCritic:
        {enabled: true, cost_power: 1, cost_weight: 5.0, threshold_to_consider: 0.5}
      CostCritic:
        enabled: true
        cost_power: 1
        cost_weight: 3.81
        near_collision_cost: 253
        critical_cost: 300.0
        consider_footprint: false
        collision_cost: 1000000.0
        near_goal_distance: 1.0
        trajectory_point_step: 2
      PathAlignCritic:
        enabled: true
        cost_power: 1
        cost_weight: 14.0
        max_path_occupancy_ratio: 0.05
        trajectory_point_step: 4
        threshold_to_consider: 0.5
        offset_from_furthest: 20
        use_path_orientations: false
      PathFollowCritic:
        {enabled: true, cost_power: 1, cost_weight: 5.0, offset_from_furthest: 5,
         threshold_to_consider: 1.4}
      PathAngleCritic:
        enabled: true
        cost_power: 1
        cost_weight: 2.0
        offset_from_furthest: 4
        threshold_to_consider: 0.5
        max_angle_to_furthest: 1.0
        mode: 0
"""
FOLLOW_PATH = re.compile(r"    FollowPath:\n(?:      .*\n)+")
NATIVE_TIME = re.compile(r"Control loop execution time: (\d+) \[ms\]")
OUR_TIME = re.compile(r"compute: (\d+\.\d+) ms")
PLANNER = ("--serve", f"{nav2_testing.PREFIX}/GridBased=nav2_pyif_planners.astar:AStar")


def _params(text: str, rollouts: int, native: bool) -> str:
    """nav2_params.yaml with the MPPI block as FollowPath: Nav2's plugin, or PyController with
    the block's key and Zenoh lines kept (the parameters then reach the Python controller)."""
    block = FOLLOW_PATH.search(text)
    assert block is not None, "nav2_params.yaml has no FollowPath block"
    if native:
        plugin = f'      plugin: "{NATIVE}"'
    else:
        kept = [
            line
            for line in block.group(0).splitlines()[1:]
            if line.split(":")[0].strip() in ("plugin", "key", "zenoh_connect", "zenoh_config")
        ]
        plugin = "\n".join([*kept, "      timeout: 0.5", "      wait_for_host: 60.0"])
    mppi = MPPI_BLOCK.replace("@PLUGIN@", plugin).replace("@ROLLOUTS@", str(rollouts))
    return text.replace(block.group(0), mppi)


@dataclass
class Drive:
    seconds: float
    metres: float
    gaps: list[float] = field(default_factory=list)  # [s] between cmd_vel messages
    cpu_s: float = 0.0  # of the processes doing the controller's work


def _cpu_seconds(pids: list[int]) -> float:
    """User + system CPU of ``pids`` and their children so far."""
    import psutil

    total = 0.0
    for pid in pids:
        try:
            process = psutil.Process(pid)
            for p in (process, *process.children(recursive=True)):
                times = p.cpu_times()
                total += times.user + times.system
        except psutil.NoSuchProcess:
            continue
    return total


def _drive(client: Any, goal: tuple[float, float], workers: list[int]) -> Drive:
    """Plan to ``goal`` (the A* host), then FollowPath to it, recording what was driven."""
    from geometry_msgs.msg import Twist

    planned = client.plan(*goal)
    assert planned is not None and len(planned.result.path.poses) > 1, "no plan"
    stamps: list[float] = []
    poses: list[tuple[float, float]] = []
    commands = client.create_subscription(
        Twist, "cmd_vel", lambda _msg: stamps.append(time.monotonic()), 50
    )
    cpu = _cpu_seconds(workers)
    started = time.monotonic()
    handle = client.follow(planned.result.path)
    result_future = handle.get_result_async()
    while not result_future.done() and time.monotonic() - started < 120.0:
        client.spin_until(result_future.done, 0.05)
        if client.pose is not None:
            poses.append(client.pose)
    seconds = time.monotonic() - started
    client.destroy_subscription(commands)
    result = result_future.result() if result_future.done() else None
    assert result is not None and result.status == nav2_testing.SUCCEEDED, (
        f"FollowPath to {goal} ended {None if result is None else result.status}"
    )
    metres = sum(math.dist(a, b) for a, b in itertools.pairwise(poses))
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    return Drive(seconds, metres, gaps, _cpu_seconds(workers) - cpu)


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


@pytest.fixture(params=[(n, c) for n in ROLLOUTS for c in ["native", *OURS]])
def stack(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[dict[str, Any]]:
    rollouts, controller = request.param
    native = controller == "native"
    if native and nav2_testing.find("share/nav2_mppi_controller/package.xml") is None:
        pytest.skip("the side-by-side needs nav2_mppi_controller: testenv/build.sh jazzy mppi")
    serve = () if native else ("--serve", f"{nav2_testing.PREFIX}/FollowPath={controller}")
    for up in nav2_testing.bring_up(
        tmp_path_factory.mktemp(f"mppi_{controller.replace(':', '_')}_{rollouts}"),
        planners=(*("--path", str(nav2_testing.HERE / "planners")), *serve, *PLANNER),
        edit_params=lambda text: _params(text, rollouts, native),
    ):
        states = up["client"].wait_active(nav2_testing.SERVERS, 180.0)
        assert all(s == "active" for s in states.values()), states
        yield {**up, "rollouts": rollouts, "controller": controller, "native": native}


def test_mppi_side_by_side(stack: dict[str, Any]) -> None:
    client, procs = stack["client"], stack["procs"]
    worker = "controller_server" if stack["native"] else "planner_host"
    pids = [procs.procs[worker].pid]
    log = worker
    drives = [_drive(client, goal, pids) for _ in range(RUNS) for goal in GOALS]
    pattern = NATIVE_TIME if stack["native"] else OUR_TIME
    computes = [float(ms) for ms in pattern.findall(procs.log(log, 1_000_000))]
    assert computes, f"no compute times in {log}'s log:\n{procs.log(log, 40)}"
    cycles = sum(len(d.gaps) + 1 for d in drives)
    gaps = [g for d in drives for g in d.gaps]
    name = f"mppi_{'native' if stack['native'] else stack['controller'].split(':')[-1]}"
    name += f"_{stack['rollouts']}"
    figures: dict[str, float | int | str] = {
        f"{name}_compute_median_ms": statistics.median(computes),
        f"{name}_compute_p99_ms": _percentile(computes, 0.99),
        f"{name}_cpu_per_cycle_ms": 1e3 * sum(d.cpu_s for d in drives) / cycles,
        f"{name}_gap_median_ms": 1e3 * statistics.median(gaps),
        f"{name}_gap_p99_ms": 1e3 * _percentile(gaps, 0.99),
        f"{name}_gap_max_ms": 1e3 * max(gaps),
        f"{name}_time_to_goal_s": " / ".join(
            f"{statistics.median(d.seconds for d in drives[i :: len(GOALS)]):.2f}"
            for i in range(len(GOALS))
        ),
        f"{name}_path_m": " / ".join(
            f"{statistics.median(d.metres for d in drives[i :: len(GOALS)]):.2f}"
            for i in range(len(GOALS))
        ),
        f"{name}_drives": len(drives),
    }
    record(**figures)
    print(name, figures)
