"""Nav2 as its users launch it: nav2_bringup's own loopback-simulation launch
(tb3_loopback_simulation.launch.py: bringup_launch.py with map_server, Nav2's loopback simulator
and robot_state_publisher) and its own nav2_params.yaml, changed only in the plugin lines:

- FollowPath: PyController, served by the reference regulated pure pursuit;
- GridBased: PyGlobalPlanner, served by the reference A*;
- progress_checker: PyProgressChecker, served by the Python SimpleProgressChecker;

each given its key and the planner host's endpoint. One planner host, started beside the
launch as a user would, serves the three.

- Composed (nav2_bringup's default: every server a component of one
  component_container_isolated) and not composed, NavigateToPose goals succeed with no
  recovery.
- The unchanged stock params (Nav2's MPPI and NavFn) drive the same goals: the Python-planned
  stack's time to the goals is within 10 % of theirs (both printed, and recorded in
  $NAV2_PYIF_FIGURES).
- The planner host SIGKILLed mid-goal and restarted 2 s later costs at most one recovery; while
  it is dead the container does not stall: every lifecycle bond's heartbeats and both
  costmaps' footprints keep at least half their rate, and no server is reported down.
- Ctrl-C on the launch (SIGINT to its process group) ends every process it started.

Needs, beyond what test_nav2_pyif.py needs: nav2_bringup, nav2_loopback_sim,
robot_state_publisher, nav2_minimal_tb3_sim, rclcpp_components, `ros2 launch` and, for the
native comparison, nav2_mppi_controller (testenv/build.sh jazzy builds the first ones, then
`testenv/build.sh jazzy mppi`). Skipped, naming what is missing, otherwise.
"""

from __future__ import annotations

import re
import shutil
import signal
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record

pytestmark = pytest.mark.timeout(900)

PREFIX = nav2_testing.PREFIX
STOCK_PARAMS = "share/nav2_bringup/params/nav2_params.yaml"
LAUNCH = ("nav2_bringup", "tb3_loopback_simulation.launch.py")
# The TurtleBot 3 sandbox (nav2_bringup's default map): the robot starts where the TurtleBot 3
# simulation spawns it, drives up around the pillars and back.
START = (-2.0, -0.5)
GOALS = ((0.5, 1.7), START)
# The plugin lines changed, and the Python planner that serves each.
PYTHON_PLUGINS = {
    "nav2_mppi_controller::MPPIController": (
        "nav2_pyif_bridge::PyController",
        "FollowPath",
        "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
    ),
    "nav2_navfn_planner::NavfnPlanner": (
        "nav2_pyif_bridge::PyGlobalPlanner",
        "GridBased",
        "nav2_pyif_planners.astar:AStar",
    ),
    "nav2_controller::SimpleProgressChecker": (
        "nav2_pyif_bridge::PyProgressChecker",
        "progress_checker",
        "nav2_pyif_planners.checker_plugins:SimpleProgressChecker",
    ),
}
# nav2_bringup's navigation_launch.py: the nodes of lifecycle_manager_navigation.
NAVIGATION = (
    "controller_server",
    "smoother_server",
    "planner_server",
    "behavior_server",
    "velocity_smoother",
    "collision_monitor",
    "bt_navigator",
    "waypoint_follower",
    "docking_server",
)
FAULT_AT, RESTART_AFTER = 3.0, 2.0  # [s] into the goal; [s] after the kill
# Rates the container's other work keeps while a Python call fails, at least this share of
# their healthy rate.
KEPT_RATE = 0.5
# Time to the goals, Python-planned against native, at most this far apart.
WITHIN = 0.10
FOOTPRINTS = ("/local_costmap/published_footprint", "/global_costmap/published_footprint")
# What lifecycle_manager logs when a server's bond misses its heartbeats.
SERVER_DOWN = re.compile(r"Have not received a heartbeat|IS DOWN")


def _missing(native: bool) -> list[str]:
    absent = nav2_testing.missing()
    if shutil.which("ros2") is None:
        absent.append("the ros2 command (ros2cli)")
    needed = {
        "nav2_bringup": f"share/{LAUNCH[0]}/launch/{LAUNCH[1]}",
        "nav2_loopback_sim": "lib/nav2_loopback_sim/loopback_simulator",
        "robot_state_publisher": "lib/robot_state_publisher/robot_state_publisher",
        "nav2_minimal_tb3_sim": "share/nav2_minimal_tb3_sim/urdf/turtlebot3_waffle.urdf",
        "rclcpp_components": "lib/rclcpp_components/component_container_isolated",
    }
    if native:
        needed["nav2_mppi_controller (testenv/build.sh jazzy mppi)"] = (
            "share/nav2_mppi_controller/package.xml"
        )
    absent += [name for name, path in needed.items() if nav2_testing.find(path) is None]
    try:
        import bond.msg  # noqa: F401
    except ImportError:
        absent.append("bond's messages (bond_core)")
    return absent


def python_params(stock: str, zenoh: str) -> str:
    """nav2_bringup's params with only the plugin lines changed: each plugin of
    PYTHON_PLUGINS becomes its nav2_pyif plugin, with the key its host serves and ``zenoh``
    (the line that names the host's endpoint). Every other line, the native plugins' own
    parameters included (the Python planners are given them and ignore those they do not
    declare), is kept."""
    out, changed = [], []
    for line in stock.splitlines():
        found = re.fullmatch(r'(\s+)plugin: "([^"]+)"\s*', line)
        if found and found.group(2) in PYTHON_PLUGINS:
            indent, native = found.groups()
            plugin, name, _ = PYTHON_PLUGINS[native]
            out += [
                f'{indent}plugin: "{plugin}"',
                f'{indent}key: "{PREFIX}/{name}"',
                f"{indent}{zenoh}",
            ]
            changed.append(native)
        else:
            out.append(line)
    assert sorted(changed) == sorted(PYTHON_PLUGINS), f"the stock params changed: {changed}"
    return "\n".join(out) + "\n"


def _host_arguments(endpoint: str) -> list[str]:
    served = [
        argument
        for _, name, planner in PYTHON_PLUGINS.values()
        for argument in ("--serve", f"{PREFIX}/{name}={planner}")
    ]
    return [*(nav2_testing.host_command() or []), "--listen", endpoint, *served]


@dataclass
class Stack:
    client: Any
    procs: nav2_testing.Processes
    start_host: Any  # () -> None; None for the native stack
    # (monotonic time, source): each bond heartbeat ("bond:<node>") and footprint received
    events: list[tuple[float, str]] = field(default_factory=list)

    def launched(self) -> set[str]:
        """The names of the processes the launch runs (comm: their first 15 characters)."""
        launch = self.procs.procs["launch"].pid
        return {nav2_testing.comm(p) for p in nav2_testing.descendants(launch)}

    def rates(self, start: float, end: float) -> dict[str, float]:
        counts: dict[str, int] = {}
        for stamp, source in self.events:
            if start <= stamp < end:
                counts[source] = counts.get(source, 0) + 1
        return {source: count / (end - start) for source, count in counts.items()}


@contextmanager
def stock_bringup(logs: Path, python: bool, composed: bool) -> Iterator[Stack]:
    """nav2_bringup's loopback launch with its params (the Python plugins' when ``python``,
    with their planner host), composed or not; the robot put at START; every lifecycle node
    active. Skips, naming what is missing, where the environment lacks a part."""
    missing = _missing(native=not python)
    if missing:
        pytest.skip("the stock nav2_bringup test needs: " + ", ".join(missing))
    stock = nav2_testing.find(STOCK_PARAMS)
    assert stock is not None
    procs = nav2_testing.processes_in_own_domain(logs)
    params = logs / "nav2_params.yaml"
    start_host = None
    if python:
        endpoint = f"tcp/127.0.0.1:{nav2_testing.free_port()}"
        params.write_text(
            python_params(stock.read_text(), nav2_testing.plugin_zenoh(logs, endpoint))
        )

        def start_host() -> None:
            procs.start("planner_host", _host_arguments(endpoint))

        start_host()
    else:
        params.write_text(stock.read_text())
    procs.start(
        "launch",
        [
            *("ros2", "launch", *LAUNCH),
            f"params_file:={params}",
            "use_rviz:=False",
            f"use_composition:={composed}",
        ],
    )
    import rclpy
    from bond.msg import Status
    from geometry_msgs.msg import PolygonStamped, PoseWithCovarianceStamped
    from rclpy.qos import qos_profile_sensor_data

    rclpy.init()
    client = nav2_testing.Nav2Client()
    stack = Stack(client, procs, start_host)

    def heard(source: str) -> None:
        stack.events.append((time.monotonic(), source))

    # best effort: matches the publishers whichever reliability they offer
    client.create_subscription(
        Status, "/bond", lambda m: heard(f"bond:{m.id}"), qos_profile_sensor_data
    )
    for topic in FOOTPRINTS:
        client.create_subscription(
            PolygonStamped, topic, lambda _m, t=topic: heard(t), qos_profile_sensor_data
        )
    initial_pose = client.create_publisher(PoseWithCovarianceStamped, "/initialpose", 10)
    pose = PoseWithCovarianceStamped()
    pose.header.frame_id = "map"
    pose.pose.pose.position.x, pose.pose.pose.position.y = START
    pose.pose.pose.orientation.w = 1.0
    try:
        # The loopback simulator places the robot where the initial pose says (as RViz's
        # "2D Pose Estimate" does); the costmaps activate once map -> base_link exists.
        deadline = time.monotonic() + 240.0
        states: dict[str, str | None] = {}
        while time.monotonic() < deadline:
            initial_pose.publish(pose)
            states = client.wait_active(NAVIGATION, 2.0)
            if all(s == "active" for s in states.values()):
                break
        assert all(s == "active" for s in states.values()), f"{states}\n{procs.log('launch', 80)}"
        yield stack
    finally:
        client.destroy_node()
        rclpy.try_shutdown()
        procs.stop_all()


@dataclass
class Run:
    succeeded: bool
    seconds: float
    recoveries: int
    status: int


def navigate(stack: Stack, goal: tuple[float, float], fault: Any = None) -> Run:
    """NavigateToPose to ``goal`` through bt_navigator's default tree; ``fault`` (if any) is
    called FAULT_AT s in."""
    client = stack.client
    handle = client.navigate(*goal)
    started = time.monotonic()
    result_future = handle.get_result_async()
    if fault is not None:
        client.spin_until(result_future.done, FAULT_AT)
        assert not result_future.done(), "the goal ended before its fault"
        fault()
    result = client.wait(result_future, 180.0)
    client.recording = False
    status = -1 if result is None else int(result.status)
    return Run(
        status == nav2_testing.SUCCEEDED, time.monotonic() - started, client.recoveries, status
    )


def drive_the_goals(stack: Stack, label: str) -> list[float]:
    """Every goal of GOALS, each succeeding with no recovery: the seconds each took."""
    seconds = []
    for goal in GOALS:
        run = navigate(stack, goal)
        assert run.succeeded and run.recoveries == 0, (
            f"{label} to {goal}: {run}\n" + stack.procs.log("launch", 80)
        )
        seconds.append(run.seconds)
    record(**{f"bringup_{label}_to_goal_{i}_s": s for i, s in enumerate(seconds)})
    print(label, "seconds to each goal:", [round(s, 2) for s in seconds])
    return seconds


def assert_ctrl_c_ends_everything(stack: Stack) -> None:
    launch = stack.procs.procs["launch"]
    started = {nav2_testing.comm(p) for p in nav2_testing.descendants(launch.pid)}
    code, left = nav2_testing.ctrl_c(launch)
    assert not left, f"still running after Ctrl-C: {left} (of {started})\n" + stack.procs.log(
        "launch", 60
    )
    assert code == 0, f"ros2 launch exited {code}\n{stack.procs.log('launch', 60)}"


# Seconds to each goal, by configuration, for the comparison at the end.
TIMES: dict[str, list[float]] = {}


def test_the_unchanged_stock_stack_drives_the_goals(tmp_path: Path) -> None:
    with stock_bringup(tmp_path, python=False, composed=True) as stack:
        TIMES["native"] = drive_the_goals(stack, "native")
        assert_ctrl_c_ends_everything(stack)


def test_python_plugins_composed_reach_the_goals_and_survive_a_killed_host(
    tmp_path: Path,
) -> None:
    with stock_bringup(tmp_path, python=True, composed=True) as stack:
        names = stack.launched()
        assert "component_conta" in names, names  # one container, composed (comm: 15 chars)
        assert "controller_serv" not in names, names
        TIMES["python_composed"] = drive_the_goals(stack, "python_composed")

        procs = stack.procs
        killed: list[float] = []

        def kill_and_restart() -> None:
            procs.kill("planner_host", signal.SIGKILL)
            killed.append(time.monotonic())
            stack.client.spin_until(lambda: False, RESTART_AFTER)
            assert stack.start_host is not None
            stack.start_host()

        run = navigate(stack, GOALS[0], kill_and_restart)
        logs = procs.log("launch", 120) + "\n" + procs.log("planner_host", 40)
        assert run.succeeded, f"NavigateToPose with the host killed: {run}\n{logs}"
        assert run.recoveries <= 1, f"{run}\n{logs}"
        record(
            bringup_host_killed_s=run.seconds,
            bringup_host_killed_recoveries=run.recoveries,
        )
        # The container did not stall while the host was dead: the healthy rates are the
        # previous goals' (the robot driving), the dead window the host's downtime.
        healthy = stack.rates(killed[0] - 20.0, killed[0] - 1.0)
        # (dead, then starting: the host answers again only once it has imported its planners)
        dead = stack.rates(killed[0], killed[0] + RESTART_AFTER + 1.0)
        print("rates [1/s] healthy:", healthy, "host dead:", dead)
        bonds = [s for s in healthy if s.startswith("bond:")]
        assert len(bonds) >= len(NAVIGATION), f"bonds heard: {bonds}"
        for source in [*bonds, *FOOTPRINTS]:
            assert source in healthy, f"never heard {source}: {healthy}"
            assert dead.get(source, 0.0) >= KEPT_RATE * healthy[source], (
                f"{source} fell from {healthy[source]:.1f}/s to {dead.get(source, 0.0):.1f}/s "
                f"while the host was dead\n{logs}"
            )
        down = [
            line for line in procs.log("launch", 100_000).splitlines() if SERVER_DOWN.search(line)
        ]
        assert not down, "\n".join(down)
        states = stack.client.wait_active(NAVIGATION, 10.0)
        assert all(s == "active" for s in states.values()), states
        assert_ctrl_c_ends_everything(stack)


def test_python_plugins_not_composed_reach_the_goals(tmp_path: Path) -> None:
    with stock_bringup(tmp_path, python=True, composed=False) as stack:
        names = stack.launched()
        assert {"controller_serv", "planner_server"} <= names, names  # a process each
        TIMES["python_separate"] = drive_the_goals(stack, "python_separate")
        assert_ctrl_c_ends_everything(stack)


def test_time_to_the_goals_within_ten_percent_of_native() -> None:
    for needed in ("native", "python_composed", "python_separate"):
        if needed not in TIMES:
            pytest.skip(
                f"the comparison needs the {needed} run of this module, which did not finish"
            )
    native = sum(TIMES["native"])
    rows = [f"{'stack':<16} {'goal 0 [s]':>10} {'goal 1 [s]':>10} {'total [s]':>10} {'ratio':>6}"]
    for label, seconds in TIMES.items():
        total = sum(seconds)
        rows.append(
            f"{label:<16} {seconds[0]:>10.2f} {seconds[1]:>10.2f} {total:>10.2f} "
            f"{total / native:>6.2f}"
        )
    print("\n".join(rows))
    record(**{f"bringup_{label}_ratio": sum(s) / native for label, s in TIMES.items()})
    for label in ("python_composed", "python_separate"):
        ratio = sum(TIMES[label]) / native
        assert abs(ratio - 1.0) <= WITHIN, f"{label}: {ratio:.2f} x native\n" + "\n".join(rows)
