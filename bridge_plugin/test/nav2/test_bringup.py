"""Nav2 as its users launch it: nav2_bringup's own loopback-simulation launch
(tb3_loopback_simulation.launch.py: bringup_launch.py with map_server, Nav2's loopback simulator
and robot_state_publisher) and its own nav2_params.yaml, changed only in the plugin lines.
Humble's navigation2 (1.1) has no loopback simulator and no such launch: there
humble_loopback_launch.py stands in for the launch, doing what Jazzy's does with nav2_bringup's
navigation_launch.py, map_server, robot_state_publisher and Jazzy's loopback simulator (built
on Humble by testenv/build.sh). The plugin lines changed:

- FollowPath: PyController, served by the reference regulated pure pursuit;
- GridBased: PyGlobalPlanner, served by the reference A*;
- progress_checker: PyProgressChecker, served by the Python SimpleProgressChecker;

each given its key and where to meet the planner host. Beside those, every stack (native
ones too) waits 200 ms instead of the stock 20 ms for a server to take bt_navigator's goals,
and the stacks facing a killed host get a failure_tolerance that covers its restart (the
constants below say why). One planner host, started beside the
launch as a user would, serves the three: it listens on a free port the plugins dial, or, on
rmw_zenoh ($NAV2_PYIF_SHARED_ROUTER, set by tests/test_nav2_launch.py), plugins and host meet at
rmw_zenoh's own router.

- Composed (nav2_bringup's default: every server a component of one
  component_container_isolated) and not composed, NavigateToPose goals succeed with no
  recovery.
- Nav2's own regulated pure pursuit (the algorithm the Python stacks serve), composed and
  not, drives the same goals: each Python-planned stack's time to the goals is within 10 % of
  the native stack run the same way (each goal driven twice, its faster run counted, on both
  sides). Time to a goal is the robot's: the loopback simulator's steps from the goal to its
  result times its update_duration (each step moves the robot by one period's worth, and a
  simulator short of CPU steps late: wall time would measure its share of the two cores,
  which the Python stacks' host and workers take from). The unchanged stock params (Nav2's
  MPPI and NavFn; Humble's DWB) are shown beside them (all printed side by side, and recorded in
  $NAV2_PYIF_FIGURES).
- Composed and not, the planner host SIGKILLed mid-goal and restarted 2 s later costs at most
  one recovery. Composed, the host also stops answering for 2 s mid-goal (SIGSTOP: every call
  runs into its timeout, a slow Python call as Nav2 sees it), and the goal still succeeds.
  While the host is slow or dead the container does not stall: every lifecycle bond's
  heartbeats and both costmaps' footprints keep at least half their rate, and no server is
  reported down.
- Local-host mode (the plugins start their own planner hosts: `python_planner`, no key) inside
  the composed container drives the goals; `ros2 lifecycle set /controller_server shutdown`
  then ends every process its plugins started (keeper, host, workers) while the container and
  planner_server's hosts stay up, and Ctrl-C ends those.
- The controller and global planner a new user writes in the tutorials (GoTo, GridSearch, taken
  from python/doc/tutorials as the pages show them) drive the stock launch to the goals: what
  the tutorials promise a new user, in Nav2.
- Ctrl-C on the launch (SIGINT to its process group) ends every process it started.

Needs, beyond what test_nav2_pyif.py needs: nav2_bringup, nav2_loopback_sim,
robot_state_publisher, nav2_minimal_tb3_sim (Humble: nav2_bringup's own TurtleBot 3 URDF),
rclcpp_components, `ros2 launch`, `ros2 lifecycle` and, for the native comparison, the stock
controller's package (nav2_mppi_controller: `testenv/build.sh jazzy mppi`; Humble's dwb_core).
Skipped, naming what is missing, otherwise.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record

from tests.docs_blocks import used_files

pytestmark = pytest.mark.timeout(1200)

PREFIX = nav2_testing.PREFIX
# The loopback launch: Jazzy's name, and Lyrical's. Humble's nav2_bringup has none (no
# nav2_loopback_sim in navigation2 1.1): the stand-in beside this file runs its parts.
LAUNCHES = ("tb3_loopback_simulation.launch.py", "tb3_loopback_simulation_launch.py")
HUMBLE_LAUNCH = nav2_testing.HERE / "humble_loopback_launch.py"
BRINGUP_SHARE = "share/nav2_bringup"
# The TurtleBot 3 sandbox (nav2_bringup's default map): the robot starts where the TurtleBot 3
# simulation spawns it, drives up around the pillars and back.
START = (-2.0, -0.5)
GOALS = ((0.5, 1.7), START)
# The plugins changed, by server and plugin name (the same names on Humble, Jazzy and
# Lyrical), and the Python plugin and planner that serve each.
Plugins = dict[tuple[str, str], tuple[str, str]]
PYTHON_PLUGINS: Plugins = {
    ("controller_server", "FollowPath"): (
        "nav2_pyif_bridge::PyController",
        "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
    ),
    ("planner_server", "GridBased"): (
        "nav2_pyif_bridge::PyGlobalPlanner",
        "nav2_pyif_planners.astar:AStar",
    ),
    ("controller_server", "progress_checker"): (
        "nav2_pyif_bridge::PyProgressChecker",
        "nav2_pyif_planners.checker_plugins:SimpleProgressChecker",
    ),
}
# The tutorials' controller and global planner (python/doc/tutorials), as a new user writes
# them, in place of the stock controller and planner.
TUTORIAL_PLUGINS: Plugins = {
    ("controller_server", "FollowPath"): (
        "nav2_pyif_bridge::PyController",
        "my_planners.go_to:GoTo",
    ),
    ("planner_server", "GridBased"): (
        "nav2_pyif_bridge::PyGlobalPlanner",
        "my_planners.grid_search:GridSearch",
    ),
}
ROOT = nav2_testing.HERE.parents[2]
# The servers that hold a Python plugin (each starts its own hosts in local-host mode).
PYTHON_SERVERS = ("controller_server", "planner_server")
# nav2_bringup's navigation_launch.py names the nodes of lifecycle_manager_navigation
# (Jazzy adds collision_monitor and docking_server, Lyrical route_server and following_server).
LIFECYCLE_NODES = re.compile(r"lifecycle_nodes = \[([^\]]*)\]")
FAULT_AT, RESTART_AFTER = 3.0, 2.0  # [s] into the goal; [s] after the kill
SLOW_FOR = 2.0  # [s] the host does not answer (SIGSTOP), FAULT_AT into a goal
# Rates the container's other work keeps while a Python call fails, at least this share of
# their healthy rate.
KEPT_RATE = 0.5
HEALTHY_WINDOW = 20.0  # [s] before the first fault: the rates of a healthy stack
# Time to the goals, Python-planned against native, at most this far apart.
WITHIN = 0.10
# Each stack drives its goals this many times; each goal counts its fastest. A loaded machine
# only ever slows a run (a late first plan, a missed control period): the fastest of two
# says what the stack does, on both sides of the comparison alike.
ROUND_TRIPS = 2
# The native side of that comparison: the stock params with Nav2's own regulated pure pursuit
# as FollowPath, the algorithm the Python stacks serve (the stock MPPI drives differently: a
# comparison with it measures the controllers, not the bridge).
NATIVE_RPP = nav2_testing.NATIVE_PURE_PURSUIT
# The stacks that face a killed or stopped host give controller_server a failure_tolerance
# that covers the outage: the stock 0.3 s turns a host restart (RESTART_AFTER, then about
# 2.5 s of imports here) into recoveries, and the full-stack suite's 3.0 s ran out too.
STOCK_TOLERANCE, FAULT_TOLERANCE = "failure_tolerance: 0.3", "failure_tolerance: 6.0"
FOOTPRINTS = ("/local_costmap/published_footprint", "/global_costmap/published_footprint")
# What lifecycle_manager logs when a server's bond misses its heartbeats.
SERVER_DOWN = re.compile(r"Have not received a heartbeat|IS DOWN")
# bt_navigator's wait for a server to take a goal, 20 ms in the stock params: on a loaded
# 2-core machine every stack, the stock one too, lost goals to it mid-way ("Timed out while
# waiting for action server to acknowledge goal request"). Every stack here, native and
# Python alike, gets 200 ms: a change beside the plugin lines, the same on both sides.
STOCK_SERVER_WAIT, LOADED_SERVER_WAIT = "default_server_timeout: 20", "default_server_timeout: 200"
DIED = "process has died"  # what `ros2 launch` logs when one of its processes ends
CONTAINER = "component_conta"  # component_container_isolated, as /proc/PID/comm cuts it
KEY_LINE = re.compile(r"(\s*)([A-Za-z_][\w]*):(.*)")


def plugin_lines(stock: str) -> Iterator[tuple[str, tuple[str, str] | None]]:
    """Each line of a Nav2 params file, with the plugin it names when it is a plugin's
    `plugin:` line (server and plugin name: ("controller_server", "FollowPath")), else None."""
    path: list[tuple[int, str]] = []  # (indent, key) of the line and its parents
    for line in stock.splitlines():
        found = KEY_LINE.fullmatch(line)
        role = None
        if found and not line.lstrip().startswith("#"):
            indent = len(found.group(1))
            path = [(i, k) for i, k in path if i < indent] + [(indent, found.group(2))]
            keys = [key for _, key in path]
            if len(keys) == 4 and keys[1] == "ros__parameters" and keys[3] == "plugin":
                role = (keys[0], keys[2])
        yield line, role


def native_plugins(stock: str) -> dict[tuple[str, str], str]:
    """The stock plugin type of each plugin PYTHON_PLUGINS replaces."""
    return {
        role: line.split(":", 1)[1].strip().strip("'\"")
        for line, role in plugin_lines(stock)
        if role in PYTHON_PLUGINS
    }


def python_params(
    stock: str, serve: Callable[[str, str], list[str]], plugins: Plugins = PYTHON_PLUGINS
) -> str:
    """nav2_bringup's params with only the plugin lines changed: each plugin of ``plugins``
    becomes its nav2_pyif plugin, followed by the lines ``serve(name, planner)`` gives (where
    the host is: a key and the Zenoh line, or the local host's planner). Every other line, the
    native plugins' own parameters included (the Python planners are given them and ignore
    those they do not declare), is kept."""
    out, changed = [], []
    for line, role in plugin_lines(stock):
        if role not in plugins:
            out.append(line)
            continue
        assert role is not None
        indent = line[: len(line) - len(line.lstrip())]
        plugin, planner = plugins[role]
        out += [f'{indent}plugin: "{plugin}"', *(indent + s for s in serve(role[1], planner))]
        changed.append(role)
    assert sorted(changed) == sorted(plugins), f"the stock params changed: {changed}"
    return "\n".join(out) + "\n"


def native_rpp_params(stock: str) -> str:
    """The stock params with Nav2's regulated pure pursuit as FollowPath (every other line,
    the stock controller's own parameters included, kept: RPP ignores them)."""
    out = []
    for line, role in plugin_lines(stock):
        if role == ("controller_server", "FollowPath"):
            line = line.split(":", 1)[0] + f': "{NATIVE_RPP}"'
        out.append(line)
    return "\n".join(out) + "\n"


def _native_package(stock: str) -> str:
    """The package of the stock controller (nav2_mppi_controller, dwb_core, ...)."""
    controller = native_plugins(stock)[("controller_server", "FollowPath")]
    return re.split(r"::|/", controller)[0]


def _missing(native: bool, local: bool) -> list[str]:
    absent = nav2_testing.missing()
    if shutil.which("ros2") is None:
        absent.append("the ros2 command (ros2cli)")
    launch = _launch()
    needed = {
        # (Humble's stand-in: nav2_bringup's navigation launch and TurtleBot 3 URDF)
        **(
            {
                "nav2_bringup's launch": f"{BRINGUP_SHARE}/launch/navigation_launch.py",
                "nav2_bringup's URDF": f"{BRINGUP_SHARE}/urdf/turtlebot3_waffle.urdf",
            }
            if launch == HUMBLE_LAUNCH
            else {
                "nav2_bringup's loopback launch": f"{BRINGUP_SHARE}/launch/{launch}",
                "nav2_minimal_tb3_sim": "share/nav2_minimal_tb3_sim/urdf/turtlebot3_waffle.urdf",
            }
        ),
        "nav2_loopback_sim": "lib/nav2_loopback_sim/loopback_simulator",
        "robot_state_publisher": "lib/robot_state_publisher/robot_state_publisher",
        # (component_container_isolated before Lyrical, component_container --isolated on it)
        "rclcpp_components": "lib/rclcpp_components/component_container",
        "ros2lifecycle (`ros2 lifecycle`)": "share/ros2lifecycle/package.xml",
    }
    stock = nav2_testing.find(nav2_testing.STOCK_PARAMS)
    if native and stock is not None:
        package = _native_package(stock.read_text())
        built_by = " (testenv/build.sh DISTRO mppi)" if package == "nav2_mppi_controller" else ""
        needed[f"the stock controller, {package}{built_by}"] = f"share/{package}/package.xml"
    absent += [name for name, path in needed.items() if nav2_testing.find(path) is None]
    host = nav2_testing.host_command()
    if local and host is not None and len(host) != 1:
        absent.append("$NAV2_PYIF_PLANNER_HOST as one executable (planner_host_command)")
    try:
        import bond.msg  # noqa: F401
    except ImportError:
        absent.append("bond's messages (bond_core)")
    return absent


@dataclass
class Stack:
    client: Any
    procs: nav2_testing.Processes
    start_host: Any  # () -> None; None for the native stack and local hosts
    step: float  # [s] the loopback simulator's update_duration: the robot's time per step
    # (monotonic time, source): each bond heartbeat ("bond:<node>") and footprint received
    events: list[tuple[float, str]] = field(default_factory=list)

    def launched(self) -> dict[int, str]:
        """The processes the launch runs, by pid: their names (comm: the first 15
        characters)."""
        launch = self.procs.procs["launch"].pid
        return {p: nav2_testing.comm(p) for p in nav2_testing.descendants(launch)}

    def container(self) -> int:
        found = [p for p, name in self.launched().items() if name == CONTAINER]
        assert len(found) == 1, f"not one component container: {self.launched()}"
        return found[0]

    def rates(self, start: float, end: float) -> dict[str, float]:
        counts: dict[str, int] = {}
        for stamp, source in self.events:
            if start <= stamp < end:
                counts[source] = counts.get(source, 0) + 1
        return {source: count / (end - start) for source, count in counts.items()}


def _separate_host(
    procs: nav2_testing.Processes, logs: Path, stock: str, plugins: Plugins, path: Path | None
) -> tuple[str, Any]:
    """The params for one planner host started beside the launch (importing planners from
    ``path`` too, when given), and the function that starts it: it listens on a free port the
    plugins dial, or, on rmw_zenoh, plugins and host connect to rmw_zenoh's router."""
    router = nav2_testing.shared_router()
    endpoint = router or f"tcp/127.0.0.1:{nav2_testing.free_port()}"
    zenoh = nav2_testing.plugin_zenoh(logs, endpoint)
    params = python_params(stock, lambda name, _: [f'key: "{PREFIX}/{name}"', zenoh], plugins)
    served = [
        argument
        for (_, name), (_, planner) in plugins.items()
        for argument in ("--serve", f"{PREFIX}/{name}={planner}")
    ]
    host = [*(nav2_testing.host_command() or []), "--connect" if router else "--listen", endpoint]
    if path is not None:
        host += ["--path", str(path)]

    def start_host() -> None:
        procs.start("planner_host", [*host, *served])

    return params, start_host


def _local_hosts(stock: str) -> str:
    """The params in which each plugin starts its own planner host (no key)."""
    host = nav2_testing.host_command()
    assert host is not None and len(host) == 1
    return python_params(
        stock,
        lambda _, planner: [f'python_planner: "{planner}"', f'planner_host_command: "{host[0]}"'],
    )


@contextmanager
def stock_bringup(
    logs: Path,
    python: bool,
    composed: bool,
    local: bool = False,
    plugins: Plugins = PYTHON_PLUGINS,
    path: Path | None = None,
    native_rpp: bool = False,
) -> Iterator[Stack]:
    """nav2_bringup's loopback launch with its params (``plugins`` changed when ``python``,
    with their planner host beside the launch, importing from ``path`` too, or started by the
    plugins when ``local``), composed or not; the robot put at START; every lifecycle node
    active. Skips, naming what is missing, where the environment lacks a part."""
    missing = _missing(native=not python, local=local)
    if missing:
        pytest.skip("the stock nav2_bringup test needs: " + ", ".join(missing))
    stock_file = nav2_testing.find(nav2_testing.STOCK_PARAMS)
    assert stock_file is not None
    stock = stock_file.read_text()
    procs = nav2_testing.processes_in_own_domain(logs)
    params = logs / "nav2_params.yaml"
    start_host = None
    if python and not local:
        text, start_host = _separate_host(procs, logs, stock, plugins, path)
        assert STOCK_TOLERANCE in text, f"no '{STOCK_TOLERANCE}' in {stock_file}"
        params.write_text(text.replace(STOCK_TOLERANCE, FAULT_TOLERANCE))
        start_host()
    elif python:
        params.write_text(_local_hosts(stock))
    else:
        params.write_text(native_rpp_params(stock) if native_rpp else stock)
    assert STOCK_SERVER_WAIT in stock, f"no '{STOCK_SERVER_WAIT}' in {stock_file}"
    params.write_text(params.read_text().replace(STOCK_SERVER_WAIT, LOADED_SERVER_WAIT))
    launch = _launch()
    procs.start(
        "launch",
        [
            *("ros2", "launch"),
            *([str(launch)] if launch == HUMBLE_LAUNCH else ["nav2_bringup", str(launch)]),
            f"params_file:={params}",
            "use_rviz:=False",
            f"use_composition:={composed}",
        ],
    )
    from bond.msg import Status
    from geometry_msgs.msg import PolygonStamped, PoseWithCovarianceStamped
    from rclpy.qos import QoSProfile, ReliabilityPolicy

    client = nav2_testing.ros_client(procs)
    base_frame, step = simulator_step(stock)
    client.count_steps(base_frame)
    stack = Stack(client, procs, start_host, step)

    def heard(source: str) -> None:
        stack.events.append((time.monotonic(), source))

    # Best effort matches the publishers whichever reliability they offer; a deep queue, so a
    # busy test process counts every message late rather than losing some.
    qos = QoSProfile(depth=500, reliability=ReliabilityPolicy.BEST_EFFORT)
    client.create_subscription(Status, "/bond", lambda m: heard(f"bond:{m.id}"), qos)
    for topic in FOOTPRINTS:
        client.create_subscription(PolygonStamped, topic, lambda _m, t=topic: heard(t), qos)
    initial_pose = client.create_publisher(PoseWithCovarianceStamped, "/initialpose", 10)
    pose = PoseWithCovarianceStamped()
    pose.header.frame_id = "map"
    pose.pose.pose.position.x, pose.pose.pose.position.y = START
    pose.pose.pose.orientation.w = 1.0
    try:
        # The loopback simulator places the robot where the initial pose says (as RViz's
        # "2D Pose Estimate" does); the costmaps activate once map -> base_link exists.
        deadline = time.monotonic() + 300.0
        states: dict[str, str | None] = {}
        while time.monotonic() < deadline:
            initial_pose.publish(pose)
            states = client.wait_active(_navigation(), 2.0)
            if all(s == "active" for s in states.values()):
                break
            # a process of the launch that died (a plugin library that fails to load) never
            # comes back: say so now rather than after the deadline
            died = [line for line in procs.log("launch", 100_000).splitlines() if DIED in line]
            assert not died, "\n".join(died) + "\n" + procs.log("launch", 60)
            if states and all(s == "inactive" for s in states.values()):
                resume_after_a_failed_activation(client, procs)
        assert all(s == "active" for s in states.values()), f"{states}\n{procs.log('launch', 80)}"
        yield stack
    finally:
        nav2_testing.tear_down(client, procs)


def resume_after_a_failed_activation(client: Any, procs: nav2_testing.Processes) -> None:
    """Activate again what the lifecycle manager left configured. Nav2's own race, not the
    plugins': on simulated time a costmap that starts activating before the loopback
    simulator's first /clock waits until 0 + 60 s, and the first clock (today's time) is past
    that, so it gives up at once ("did not become available before timeout")."""
    from nav2_msgs.srv import ManageLifecycleNodes

    if "Failed to activate" not in procs.log("launch", 100_000):
        return
    manage = client.service_client(
        ManageLifecycleNodes, "/lifecycle_manager_navigation/manage_nodes"
    )
    if manage.wait_for_service(timeout_sec=10.0):
        request = ManageLifecycleNodes.Request(command=ManageLifecycleNodes.Request.RESUME)
        client.wait(manage.call_async(request), 30.0)


def _launch() -> str | Path:
    """The loopback launch file of this nav2_bringup; on Humble's Nav2 (1.1), which has none,
    the stand-in HUMBLE_LAUNCH; else its first name (the test then skips, naming it)."""
    for name in LAUNCHES:
        if nav2_testing.find(f"{BRINGUP_SHARE}/launch/{name}") is not None:
            return name
    controller = nav2_testing.find("share/nav2_controller/package.xml")
    if controller is not None and nav2_testing.nav2_controller_version()[:2] == (1, 1):
        return HUMBLE_LAUNCH
    return LAUNCHES[0]


def simulator_step(stock: str) -> tuple[str, float]:
    """The loopback simulator's robot frame and update_duration: from the stock params'
    loopback_simulator section, or (Humble: none) humble_loopback_launch.py's."""
    section = re.search(r"^loopback_simulator:\n((?:[ #].*\n|\n)+)", stock, re.MULTILINE)
    text = section.group(1) if section else HUMBLE_LAUNCH.read_text()
    frame = re.search(r"base_frame_id\W+(\w+)", text)
    step = re.search(r"update_duration\W+([0-9.]+)", text)
    assert frame and step, f"no loopback simulator base_frame_id and update_duration in {text}"
    return frame.group(1), float(step.group(1))


def _navigation() -> tuple[str, ...]:
    """The nodes lifecycle_manager_navigation manages, as this distribution's
    navigation_launch.py names them."""
    launch = nav2_testing.find("share/nav2_bringup/launch/navigation_launch.py")
    found = LIFECYCLE_NODES.search(launch.read_text()) if launch else None
    assert found, f"no lifecycle_nodes list in {launch}"
    return tuple(re.findall(r"['\"](\w+)['\"]", found.group(1)))


@dataclass
class Run:
    succeeded: bool
    seconds: float  # [s] wall time
    robot_seconds: float  # [s] the simulator's steps times its update_duration: the robot's time
    recoveries: int
    status: int
    longest_stop: float  # [s] the robot stood still between moving


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
        status == nav2_testing.SUCCEEDED,
        time.monotonic() - started,
        client.simulator_steps * stack.step,
        client.recoveries,
        status,
        nav2_testing.longest_stop(client.speeds),
    )


def drive_the_goals(stack: Stack, label: str) -> list[float]:
    """Every goal of GOALS, ROUND_TRIPS times over, each succeeding with no recovery: the
    seconds each goal took, the fastest of its round trips."""
    seconds: list[float] = []
    for trip in range(ROUND_TRIPS):
        for i, goal in enumerate(GOALS):
            run = navigate(stack, goal)
            assert run.succeeded and run.recoveries == 0, (
                f"{label} to {goal}: {run}\n" + stack.procs.log("launch", 80)
            )
            # the robot's own time: on two loaded cores the loopback simulator steps less
            # often than its period, and each step moves the robot by one period's worth, so
            # the wall clock (and the simulated clock, the simulator's wall clock) counts how
            # much CPU the simulator got, which the stack's own processes take from it
            if trip == 0:
                seconds.append(run.robot_seconds)
            else:
                seconds[i] = min(seconds[i], run.robot_seconds)
            print(
                f"{label}, round trip {trip + 1}, goal {i}: {run.robot_seconds:.2f} s "
                f"robot's time, {run.seconds:.2f} s wall"
            )
    record(**{f"bringup_{label}_to_goal_{i}_s": s for i, s in enumerate(seconds)})
    print(label, "robot's seconds to each goal, the fastest:", [round(s, 2) for s in seconds])
    return seconds


def assert_the_container_kept_its_rates(
    stack: Stack, healthy: dict[str, float], start: float, end: float, what: str
) -> dict[str, float]:
    """Between ``start`` and ``end`` (monotonic) every bond and footprint kept KEPT_RATE of
    its ``healthy`` rate: the rates then."""
    faulty = stack.rates(start, end)
    print(f"rates [1/s] healthy: {healthy}\n{what}: {faulty}")
    bonds = [s for s in healthy if s.startswith("bond:")]
    assert len(bonds) >= len(_navigation()), f"bonds heard: {bonds}"
    for source in [*bonds, *FOOTPRINTS]:
        assert source in healthy, f"never heard {source}: {healthy}"
        assert faulty.get(source, 0.0) >= KEPT_RATE * healthy[source], (
            f"{source} fell from {healthy[source]:.1f}/s to {faulty.get(source, 0.0):.1f}/s "
            f"while {what}\n" + stack.procs.log("launch", 120)
        )
    return faulty


def assert_no_server_reported_down(stack: Stack) -> None:
    log = stack.procs.log("launch", 100_000)
    down = [line for line in log.splitlines() if SERVER_DOWN.search(line)]
    assert not down, "\n".join(down)
    states = stack.client.wait_active(_navigation(), 10.0)
    assert all(s == "active" for s in states.values()), states


def survive_a_killed_host(stack: Stack, label: str, healthy: dict[str, float]) -> None:
    """The planner host SIGKILLed FAULT_AT s into a goal and restarted RESTART_AFTER s later:
    the goal succeeds with a recovery at most, the bonds and footprints keep their rates."""
    procs = stack.procs
    killed: list[float] = []

    def kill_and_restart() -> None:
        procs.kill("planner_host", signal.SIGKILL)
        killed.append(time.monotonic())
        stack.client.spin_until(lambda: False, RESTART_AFTER)
        assert stack.start_host is not None
        stack.start_host()

    run = navigate(stack, GOALS[0], kill_and_restart)
    print(f"{label}, the host killed: {run}")
    logs = procs.log("launch", 120) + "\n" + procs.log("planner_host", 40)
    assert run.succeeded, f"NavigateToPose with the host killed: {run}\n{logs}"
    assert run.recoveries <= 1, f"{run}\n{logs}"
    # (dead, then starting: the host answers again only once it has imported its planners)
    dead = (killed[0], killed[0] + RESTART_AFTER + 1.0)
    rates = assert_the_container_kept_its_rates(stack, healthy, *dead, "the host was dead")
    record(
        **{
            f"bringup_{label}_host_killed_s": run.seconds,
            f"bringup_{label}_host_killed_recoveries": run.recoveries,
            f"bringup_{label}_host_killed_longest_stop_s": run.longest_stop,
            f"bringup_{label}_host_dead_kept_rate_min": _least_kept(healthy, rates),
        }
    )
    assert_returns_to_start(stack)


def survive_a_slow_host(stack: Stack, label: str, healthy: dict[str, float]) -> None:
    """The planner host stopped (SIGSTOP: no answer, every call runs into its timeout) for
    SLOW_FOR s FAULT_AT s into a goal: the goal succeeds, the bonds and footprints keep their
    rates."""
    host = stack.procs.procs["planner_host"]
    stopped: list[float] = []

    def stop_for_a_while() -> None:
        os.killpg(host.pid, signal.SIGSTOP)
        try:
            stopped.append(time.monotonic())
            stack.client.spin_until(lambda: False, SLOW_FOR)
        finally:
            os.killpg(host.pid, signal.SIGCONT)

    run = navigate(stack, GOALS[0], stop_for_a_while)
    print(f"{label}, the host stopped {SLOW_FOR} s: {run}")
    logs = stack.procs.log("launch", 120) + "\n" + stack.procs.log("planner_host", 40)
    assert run.succeeded, f"NavigateToPose with the host stopped {SLOW_FOR} s: {run}\n{logs}"
    slow = (stopped[0], stopped[0] + SLOW_FOR)
    rates = assert_the_container_kept_its_rates(stack, healthy, *slow, "the host was slow")
    record(
        **{
            f"bringup_{label}_host_slow_s": run.seconds,
            f"bringup_{label}_host_slow_recoveries": run.recoveries,
            f"bringup_{label}_host_slow_longest_stop_s": run.longest_stop,
            f"bringup_{label}_host_slow_kept_rate_min": _least_kept(healthy, rates),
        }
    )
    assert_returns_to_start(stack)


def _least_kept(healthy: dict[str, float], faulty: dict[str, float]) -> float:
    """The smallest share of its healthy rate any bond or footprint kept."""
    sources = [s for s in healthy if s.startswith("bond:") or s in FOOTPRINTS]
    return min(faulty.get(s, 0.0) / healthy[s] for s in sources)


def assert_returns_to_start(stack: Stack) -> None:
    run = navigate(stack, START)
    assert run.succeeded, f"back to the start: {run}\n" + stack.procs.log("launch", 80)


# Nav2 1.5.1 (Lyrical) on simulated time never ends at Ctrl-C, the unchanged stock stack as
# much as the Python-planned ones: the loopback simulator, the clock's only source, ends first,
# and each costmap's deactivation then joins its update thread, which sleeps on a clock that no
# longer moves (gdb: Costmap2DROS::on_deactivate in std::thread::join, mapUpdateLoop in
# Rate::sleep). controller_server and planner_server (composed: their container) wait for ever,
# and `ros2 launch` waits for them; their signal handler is the stuck thread, so SIGTERM ends
# the launch but not always them. So on Lyrical a launch still running LYRICAL_HANG s after
# Ctrl-C must be held up by those; then SIGTERM, and SIGKILL for those still stuck (a user's
# `kill -9`), and nothing else may be left: each plugin's own hosts end with their server.
LYRICAL_HANG = 20.0
LYRICAL_STUCK = {"component_conta", "controller_serv", "planner_server"}
# Humble's composed container (rclcpp 16.0.8) never ends at Ctrl-C either, the unchanged stock
# stack's and Nav2's own pure pursuit's as much as the Python-planned ones': after its servers'
# cleanup it hangs. `ros2 launch` mostly ends it itself (SIGTERM 5 s after the SIGINT, SIGKILL
# 10 s later), but in the stock stack's runs it sent nothing for 60 s. So on Humble, composed,
# the same as on Lyrical: held up by the container alone, then SIGTERM and SIGKILL for it.
HUMBLE_STUCK = {CONTAINER}


def assert_ctrl_c_ends_everything(stack: Stack) -> None:
    launch = stack.procs.procs["launch"]
    started = set(stack.launched().values())
    stuck = (
        LYRICAL_STUCK
        if nav2_testing.is_lyrical()
        else HUMBLE_STUCK
        if _launch() == HUMBLE_LAUNCH and CONTAINER in started
        else set()
    )
    code, left = nav2_testing.ctrl_c(launch, wait=LYRICAL_HANG if stuck else 60.0)
    log = stack.procs.log("launch", 60)
    if code is None and stuck:
        assert stuck & set(left.values()), f"Ctrl-C: still running {left}\n{log}"
        print(f"Nav2's hang at Ctrl-C (Lyrical, Humble composed): {sorted(set(left.values()))}")
        everything = dict(left)
        _, left = nav2_testing.ctrl_c(launch, sig=signal.SIGTERM)
        for pid, name in left.items():
            if name in stuck:
                os.kill(pid, signal.SIGKILL)
        left = nav2_testing.left_after(everything, 10.0)
        assert not left, f"still running after Ctrl-C, SIGTERM and Nav2's servers SIGKILLed: {left}"
        return
    assert code is not None, f"ros2 launch still runs 60 s after Ctrl-C: {left}\n{log}"
    assert not left, f"still running after Ctrl-C: {left} (of {started})\n{log}"
    assert code == 0, f"ros2 launch exited {code}\n{log}"


def lifecycle_shutdown(stack: Stack, node: str) -> None:
    """`ros2 lifecycle set /NODE shutdown`, as a user types it (no ros2 daemon left behind)."""
    done = subprocess.run(
        # (without the daemon, discovery gets --spin-time: its default found no node here)
        ["ros2", "lifecycle", "set", "--no-daemon", "--spin-time", "10", f"/{node}", "shutdown"],
        env=stack.procs.env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0 and "successful" in done.stdout, (
        f"ros2 lifecycle set /{node} shutdown: exit {done.returncode}\n{done.stdout}{done.stderr}"
    )


# Seconds to each goal, by configuration, for the comparison at the end.
TIMES: dict[str, list[float]] = {}
# The native stack each Python stack is held against (the others: the composed one). The
# plugins' own hosts in the container (python_local) are shown, not held to the 10 %: three
# hosts and their workers share the two cores with the container there.
REFERENCE = {"python_composed": "native", "python_separate": "native_separate"}


def test_the_unchanged_stock_stack_drives_the_goals(tmp_path: Path) -> None:
    with stock_bringup(tmp_path, python=False, composed=True) as stack:
        TIMES["stock"] = drive_the_goals(stack, "stock")
        assert_ctrl_c_ends_everything(stack)


def test_nav2s_own_pure_pursuit_drives_the_goals(tmp_path: Path) -> None:
    """The native side of the comparison: the algorithm the Python stacks serve, in C++."""
    with stock_bringup(tmp_path, python=False, composed=True, native_rpp=True) as stack:
        TIMES["native"] = drive_the_goals(stack, "native")
        assert_ctrl_c_ends_everything(stack)


def test_nav2s_own_pure_pursuit_not_composed_drives_the_goals(tmp_path: Path) -> None:
    """The native side of the comparison for the stacks not composed: a process a server."""
    with stock_bringup(tmp_path, python=False, composed=False, native_rpp=True) as stack:
        TIMES["native_separate"] = drive_the_goals(stack, "native_separate")
        assert_ctrl_c_ends_everything(stack)


def test_python_plugins_composed_reach_the_goals_and_survive_a_slow_and_a_killed_host(
    tmp_path: Path,
) -> None:
    with stock_bringup(tmp_path, python=True, composed=True) as stack:
        names = set(stack.launched().values())
        assert CONTAINER in names, names  # one container, composed
        assert "controller_serv" not in names, names
        TIMES["python_composed"] = drive_the_goals(stack, "python_composed")
        now = time.monotonic()
        healthy = stack.rates(now - HEALTHY_WINDOW, now)
        survive_a_slow_host(stack, "composed", healthy)
        survive_a_killed_host(stack, "composed", healthy)
        assert_no_server_reported_down(stack)
        assert_ctrl_c_ends_everything(stack)


def test_python_plugins_not_composed_reach_the_goals_and_survive_a_killed_host(
    tmp_path: Path,
) -> None:
    with stock_bringup(tmp_path, python=True, composed=False) as stack:
        names = set(stack.launched().values())
        assert {"controller_serv", "planner_server"} <= names, names  # a process each
        TIMES["python_separate"] = drive_the_goals(stack, "python_separate")
        now = time.monotonic()
        survive_a_killed_host(stack, "separate", stack.rates(now - HEALTHY_WINDOW, now))
        assert_no_server_reported_down(stack)
        assert_ctrl_c_ends_everything(stack)


def local_hosts(container: int) -> dict[str, set[int]]:
    """The planner hosts the plugins started in the container, by the node whose plugin
    started them: each keeper (a child of the container: `planner-host --respawn --key
    nav2_pyif/local/<node>/<plugin>`) and every process below it (its host, the workers)."""
    by_node: dict[str, set[int]] = {}
    for pid in nav2_testing.descendants(container):
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
            argv = Path(f"/proc/{pid}/cmdline").read_bytes().decode().split("\0")
        except OSError:
            continue
        if int(stat.rsplit(")", 1)[1].split()[1]) != container or "--key" not in argv:
            continue
        node = argv[argv.index("--key") + 1].split("/")[2]
        by_node.setdefault(node, set()).update({pid, *nav2_testing.descendants(pid)})
    return by_node


def test_local_hosts_in_the_container_end_with_a_lifecycle_shutdown_and_ctrl_c(
    tmp_path: Path,
) -> None:
    with stock_bringup(tmp_path, python=True, composed=True, local=True) as stack:
        container = stack.container()
        hosts = local_hosts(container)
        # a keeper (planner-host --respawn) per plugin, each with its host and worker
        assert sorted(hosts) == sorted(PYTHON_SERVERS), hosts
        TIMES["python_local"] = drive_the_goals(stack, "python_local")
        # controller_server's, by `ros2 lifecycle`; planner_server's, by Ctrl-C
        lifecycle_shutdown(stack, "controller_server")
        left = nav2_testing.left_after(hosts["controller_server"], 20.0)
        assert not left, (
            f"still running after `ros2 lifecycle set /controller_server shutdown`: {left}\n"
            + stack.procs.log("launch", 60)
        )
        assert stack.client.state("controller_server") == "finalized"
        assert nav2_testing.running(container), "the container ended with the shutdown"
        kept = hosts["planner_server"]
        assert all(nav2_testing.running(p) for p in kept), "planner_server's hosts ended too"
        assert_ctrl_c_ends_everything(stack)  # planner_server's hosts among them


def test_the_tutorials_planners_drive_the_stock_bringup(tmp_path: Path) -> None:
    """A new user's first hour, its Nav2 half: the controller and global planner a new user
    writes by following the tutorials (python/doc/tutorials: GoTo and GridSearch, as the pages
    show them) serve nav2_bringup's stock launch, with its params changed as
    python/doc/howto/bringup.md shows."""
    user = tmp_path / "user"
    for name, text in used_files(ROOT / "python/doc/tutorials/in_nav2.md", ROOT).items():
        (user / name).parent.mkdir(parents=True, exist_ok=True)
        (user / name).write_text(text)
    assert (user / "my_planners" / "grid_search.py").is_file(), sorted(user.rglob("*.py"))
    with stock_bringup(
        tmp_path, python=True, composed=True, plugins=TUTORIAL_PLUGINS, path=user
    ) as stack:
        runs = [navigate(stack, goal) for goal in GOALS]
        record(
            **{f"bringup_tutorial_to_goal_{i}_s": run.seconds for i, run in enumerate(runs)},
            bringup_tutorial_recoveries=sum(run.recoveries for run in runs),
        )
        print("the tutorials' planners:", runs)
        logs = stack.procs.log("launch", 80) + "\n" + stack.procs.log("planner_host", 40)
        assert all(run.succeeded for run in runs), f"{runs}\n{logs}"
        assert_ctrl_c_ends_everything(stack)


def test_time_to_the_goals_within_ten_percent_of_native() -> None:
    """Each Python stack against Nav2's own pure pursuit run the same way, composed or not:
    on two cores a composed stack shares one process's threads, and both sides pay that."""
    for needed in ("native", "native_separate", "python_composed", "python_separate"):
        if needed not in TIMES:
            pytest.skip(
                f"the comparison needs the {needed} run of this module, which did not finish"
            )
    header = f"{'stack':<16} {'goal 0 [s]':>10} {'goal 1 [s]':>10} {'total [s]':>10}"
    rows = [f"{header} {'ratio':>6}  against (the robot's time: simulator steps)"]
    for label, seconds in TIMES.items():
        against = REFERENCE.get(label, "native")
        total = sum(seconds)
        rows.append(
            f"{label:<16} {seconds[0]:>10.2f} {seconds[1]:>10.2f} {total:>10.2f} "
            f"{total / sum(TIMES[against]):>6.2f}  {against}"
        )
    print("\n".join(rows))
    record(
        **{
            f"bringup_{label}_ratio": sum(s) / sum(TIMES[REFERENCE.get(label, "native")])
            for label, s in TIMES.items()
        }
    )
    for label in ("python_composed", "python_separate"):
        ratio = sum(TIMES[label]) / sum(TIMES[REFERENCE[label]])
        assert abs(ratio - 1.0) <= WITHIN, (
            f"{label}: {ratio:.2f} x {REFERENCE[label]}\n" + "\n".join(rows)
        )
