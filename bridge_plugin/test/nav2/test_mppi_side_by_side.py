"""Nav2's own MPPI and the project's, side by side in the real controller_server: the same
Nav2 MPPI parameter block (nav2_bringup's Jazzy FollowPath, visualisation off), the same
simulated robot, NavFn's plans and goals (around the wall and back), one stack per controller and
rollout count, in one session. A benchmark, not a test of the project's behaviour: it runs
only when tests/test_nav2_launch.py is asked for it (NAV2_PYIF_MPPI_SIDE_BY_SIDE=1), and
skips, naming it, where nav2_mppi_controller is not built (testenv/build.sh jazzy mppi).

Per controller: compute per cycle (Nav2's MPPI: its own "Control loop execution time" log
lines, in us with testenv's patch, else whole ms; ours: the controller method alone,
planners/timed_mppi.py), CPU of the processes doing the work per cycle (controller_server; or
the planner host and its workers), the gaps between cmd_vel messages, FollowPath's time to
the goal (each goal's median, every drive's and their sum) and the path driven.
$NAV2_PYIF_MPPI_RUNS round trips each (default 3); $NAV2_PYIF_MPPI_ROLLOUTS the rollout counts
(default "1000 2000"); $NAV2_PYIF_MPPI_OURS the served classes (module:Class, default the
timed Nav2MPPI; timed_mppi:TimedMPPIJax is the older JAX MPPI). Figures go to
$NAV2_PYIF_FIGURES (JSON), printed by tests/test_nav2_launch.py; with $NAV2_PYIF_MPPI_TRACES
(a directory), every drive's cmd_vel and poses over time too, a JSON file per stack;
$NAV2_PYIF_MPPI_HOST_ARGS our host's options (default "--xla-threads 1"; "" for XLA's pool).
"""

from __future__ import annotations

import itertools
import json
import math
import os
import re
import statistics
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record

RUNS = int(os.environ.get("NAV2_PYIF_MPPI_RUNS", "3"))
ROLLOUTS = [int(n) for n in os.environ.get("NAV2_PYIF_MPPI_ROLLOUTS", "1000 2000").split()]
OURS = os.environ.get("NAV2_PYIF_MPPI_OURS", "timed_mppi:TimedNav2MPPI").split()
TRACES = os.environ.get("NAV2_PYIF_MPPI_TRACES", "")
# our host as the MPPI guide serves a lone robot on a small computer: one XLA thread, its step
# on one core as Nav2's MPPI runs (python/doc/howto/mppi.md)
HOST_ARGS = os.environ.get("NAV2_PYIF_MPPI_HOST_ARGS", "--xla-threads 1").split()
GOALS = ((2.0, 0.5), (0.0, 0.0))
pytestmark = pytest.mark.timeout(300 + 120 * RUNS)
NATIVE = "nav2_mppi_controller::MPPIController"

# nav2_bringup's Jazzy FollowPath block, as the planners package ships it (what a Nav2 user's
# YAML holds), visualisation off: the same for both but for the plugin line.
NAV2_BLOCK = nav2_testing.HERE.parents[2] / "planners/nav2_pyif_planners/mppi_nav2/nav2_jazzy.yaml"
FOLLOW_PATH = re.compile(r"    FollowPath:\n(?:      .*\n)+")
# Nav2's MPPI logs whole ms; testenv's patch makes it log us (a 3 ms cycle truncated to whole
# ms is up to a third off).
NATIVE_TIME = re.compile(r"Control loop execution time: (\d+) \[(ms|us)\]")
OUR_TIME = re.compile(r"compute: (\d+\.\d+) ms")
PLANNER = ("--serve", f"{nav2_testing.PREFIX}/GridBased=nav2_pyif_planners.astar:AStar")


def _mppi_block() -> str:
    """Nav2's MPPI block as the distribution's nav2_bringup has it, unindented: Jazzy's as the
    planners package ships it; Lyrical's (motion models as plugins, a trajectory validator)
    from the environment's own nav2_bringup params, which Nav2MPPI reads too."""
    if not nav2_testing.is_lyrical():
        return NAV2_BLOCK.read_text()
    stock = nav2_testing.find(nav2_testing.STOCK_PARAMS)
    assert stock is not None, f"no {nav2_testing.STOCK_PARAMS}: Lyrical's MPPI block is read there"
    block = FOLLOW_PATH.search(stock.read_text())
    assert block is not None, f"{stock} has no FollowPath block"
    return "\n".join(line[6:] for line in block.group(0).splitlines()[1:]) + "\n"


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
        # configure compiles the step (seconds here: python/doc/howto/mppi.md)
        settings = ("timeout: 0.5", "wait_for_host: 60.0", "configure_timeout: 30.0")
        plugin = "\n".join([*kept, *(f"      {line}" for line in settings)])
    lines = [
        line
        for line in _mppi_block().splitlines()
        if line.strip() and not line.lstrip().startswith("#") and not line.startswith("plugin:")
    ]
    mppi = "\n".join(["    FollowPath:", plugin, *(f"      {line}" for line in lines)]) + "\n"
    mppi = re.sub(r"\n      batch_size: \d+\n", f"\n      batch_size: {rollouts}\n", mppi)
    mppi = mppi.replace("visualize: true", "visualize: false")
    # The plans: Nav2's NavFn for both, as Nav2's own MPPI set-up pairs them (with the
    # reference A*'s plans, served beside and now unused, both MPPIs stalled at the first
    # goal in the first run: BENCHMARKS.md).
    planner = 'plugin: "nav2_pyif_bridge::PyGlobalPlanner"'
    assert planner in text, "nav2_params.yaml's GridBased is no longer PyGlobalPlanner"
    text = text.replace(planner, 'plugin: "nav2_navfn_planner::NavfnPlanner"')
    return text.replace(block.group(0), mppi)


@dataclass
class Drive:
    seconds: float
    metres: float
    gaps: list[float] = field(default_factory=list)  # [s] between cmd_vel messages
    cpu_s: float = 0.0  # of the processes doing the controller's work
    # (s since the goal was sent, vx, wz) of each cmd_vel; (s, x, y) of each pose seen
    commands: list[tuple[float, float, float]] = field(default_factory=list)
    poses: list[tuple[float, float, float]] = field(default_factory=list)


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
    """Plan to ``goal`` (NavFn), then FollowPath to it, recording what was driven."""
    from geometry_msgs.msg import Twist, TwistStamped
    from sim_robot import STAMPED_CMD_VEL  # the command's type where the robot reads it

    planned = client.plan(*goal)
    assert planned is not None and len(planned.result.path.poses) > 1, "no plan"
    heard: list[tuple[float, float, float]] = []  # (monotonic s, vx, wz) of each cmd_vel
    poses: list[tuple[float, float, float]] = []

    def hear(msg: Any) -> None:
        twist = msg.twist if STAMPED_CMD_VEL else msg
        heard.append((time.monotonic(), twist.linear.x, twist.angular.z))

    commands = client.create_subscription(
        TwistStamped if STAMPED_CMD_VEL else Twist, "cmd_vel", hear, 50
    )
    cpu = _cpu_seconds(workers)
    started = time.monotonic()
    handle = client.follow(planned.result.path)
    result_future = handle.get_result_async()
    while not result_future.done() and time.monotonic() - started < 120.0:
        client.spin_until(result_future.done, 0.05)
        if client.pose is not None:
            poses.append((time.monotonic() - started, *client.pose[:2]))
    seconds = time.monotonic() - started
    client.destroy_subscription(commands)
    result = result_future.result() if result_future.done() else None
    assert result is not None and result.status == nav2_testing.SUCCEEDED, (
        f"FollowPath to {goal} ended {None if result is None else result.status}"
    )
    metres = sum(math.dist(a[1:], b[1:]) for a, b in itertools.pairwise(poses))
    gaps = [b[0] - a[0] for a, b in itertools.pairwise(heard)]
    timeline = [(s - started, vx, wz) for s, vx, wz in heard]
    return Drive(seconds, metres, gaps, _cpu_seconds(workers) - cpu, timeline, poses)


def _per_goal(values: list[float]) -> str:
    """The median of each goal's values (drives alternate between GOALS), "a / b"."""
    return " / ".join(
        f"{statistics.median(values[i :: len(GOALS)]):.2f}" for i in range(len(GOALS))
    )


def _computes(log: str, native: bool) -> list[float]:
    """The compute times in ms that ``log`` holds: Nav2's MPPI's or ours."""
    if native:
        return [float(n) / (1e3 if unit == "us" else 1.0) for n, unit in NATIVE_TIME.findall(log)]
    return [float(ms) for ms in OUR_TIME.findall(log)]


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
    serve = (
        () if native else ("--serve", f"{nav2_testing.PREFIX}/FollowPath={controller}", *HOST_ARGS)
    )
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
    drives = [
        _drive(client, goal, [procs.procs[worker].pid]) for _ in range(RUNS) for goal in GOALS
    ]
    computes = _computes(procs.log(worker, 1_000_000), stack["native"])
    assert computes, f"no compute times in {worker}'s log:\n{procs.log(worker, 40)}"
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
        f"{name}_time_to_goal_s": _per_goal([d.seconds for d in drives]),
        f"{name}_each_drive_s": " ".join(f"{d.seconds:.2f}" for d in drives),
        # the sum: each goal's drives start from where the last one stopped, which varies
        f"{name}_all_drives_s": round(sum(d.seconds for d in drives), 2),
        f"{name}_path_m": _per_goal([d.metres for d in drives]),
        f"{name}_drives": len(drives),
    }
    record(**figures)
    print(name, figures)
    if TRACES:  # every drive's commands and poses over time, for a look at where time goes
        Path(TRACES).mkdir(parents=True, exist_ok=True)
        traces = [{"commands": d.commands, "poses": d.poses} for d in drives]
        (Path(TRACES) / f"{name}.json").write_text(json.dumps(traces))
