"""Helpers of the Nav2 launch tests: what they need, the processes they start (each in its own
process group, stopped by pid), and an rclpy client of Nav2's lifecycle and actions."""

from __future__ import annotations

import ctypes
import itertools
import json
import math
import os
import random
import re
import shlex
import shutil
import signal
import socket
import subprocess
import time
from collections.abc import Callable, Iterable, Iterator
from datetime import datetime
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
PREFIX = "nav2_pyif/launch_test"  # the keys nav2_params.yaml names
ROS_TIME = re.compile(r"^\[\w+\] \[(\d+\.\d+)\]")  # [WARN] [1763862000.123456789] [node]: ...
HOST_TIME = re.compile(r"^\[(\d{4}-\d\d-\d\d \d\d:\d\d:\d\d,\d{3})\]")  # Python logging


def prefixes() -> list[Path]:
    return [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]


def find(relative: str) -> Path | None:
    for prefix in prefixes():
        if (prefix / relative).exists():
            return prefix / relative
    return None


# nav2_bringup's own params, which users start from (under an environment's prefix)
STOCK_PARAMS = "share/nav2_bringup/params/nav2_params.yaml"


def is_lyrical() -> bool:
    """Lyrical's Nav2 (navigation2 1.5 on): its nav2_core has path_handler.hpp."""
    headers = ("include/nav2_core/nav2_core/path_handler.hpp", "include/nav2_core/path_handler.hpp")
    return any(find(header) is not None for header in headers)


def nav2_controller_version() -> tuple[int, int, int]:
    """nav2_controller's version in this environment, from its package.xml."""
    xml = find("share/nav2_controller/package.xml")
    found = re.search(r"<version>(\d+)\.(\d+)\.(\d+)</version>", xml.read_text()) if xml else None
    assert found, "no nav2_controller version in this environment"
    major, minor, patch = map(int, found.groups())
    return major, minor, patch


def costmap_wait_bounded() -> bool:
    """Whether controller_server gives up on a costmap that is not current after its
    `costmap_update_timeout` (Jazzy and later: FollowPath aborts with ControllerTimedOut), or
    waits for it without end (Humble: the goal stays active, the robot held, until the costmap
    is current again or the goal is cancelled)."""
    return nav2_controller_version()[:2] >= (1, 3)


def goal_check_first() -> bool:
    """Whether this Nav2's controller_server checks the goal first in its control cycle
    (Jazzy from 1.3.13, Kilted, Lyrical) or last (Humble, Jazzy 1.3.8 to 1.3.12), read from
    nav2_controller's package.xml (PROTOCOL.md section 15)."""
    version = nav2_controller_version()
    return version >= (1, 3, 13) if version[:2] == (1, 3) else version[:2] > (1, 3)


def project_command(name: str) -> list[str] | None:
    """A command of the nav2_pyif package (planner-host, nav2-pyif): through $NAV2_PYIF_RUN
    (a wrapper that runs its arguments in the project's environment), else from PATH."""
    wrapper = os.environ.get("NAV2_PYIF_RUN")
    if wrapper:
        return [*shlex.split(wrapper), name]
    found = shutil.which(name)
    return [found] if found else None


def host_keys(endpoint: str) -> dict[str, dict[str, Any]]:
    """Per served key, what `nav2-pyif hosts --json` says of it (queries, batch, ...)."""
    command = project_command("nav2-pyif")
    assert command is not None, "nav2-pyif is not on PATH (or $NAV2_PYIF_RUN)"
    done = subprocess.run(
        [*command, "hosts", "--json", "--connect", endpoint],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    return {k["key"]: k for host in json.loads(done.stdout)["hosts"] for k in host["keys"]}


def host_queries(endpoint: str) -> dict[str, int]:
    """Per served key, the queries the planner host has answered (`nav2-pyif hosts`)."""
    return {key: k["queries"] for key, k in host_keys(endpoint).items() if k["queries"] is not None}


def host_command() -> list[str] | None:
    """$NAV2_PYIF_PLANNER_HOST, else planner-host through $NAV2_PYIF_RUN or on PATH (pip),
    else the ROS package nav2_pyif's (a colcon workspace: `ros2 run nav2_pyif planner-host`)."""
    command = os.environ.get("NAV2_PYIF_PLANNER_HOST")
    if command:
        return shlex.split(command)
    installed = find("lib/nav2_pyif/planner-host")
    return project_command("planner-host") or ([str(installed)] if installed else None)


def missing() -> list[str]:
    absent = []
    try:
        import nav2_msgs.action  # noqa: F401
        import rclpy  # noqa: F401
    except ImportError:
        absent.append("a sourced ROS 2 with rclpy and nav2_msgs")
    for exe in (
        "lib/nav2_controller/controller_server",
        "lib/nav2_planner/planner_server",
        "lib/nav2_lifecycle_manager/lifecycle_manager",
    ):
        if find(exe) is None:
            absent.append(exe.rsplit("/", 1)[-1])
    if (
        find("share/ament_index/resource_index/nav2_core__pluginlib__plugin/nav2_pyif_bridge")
        is None
    ):
        absent.append("nav2_pyif_bridge built and sourced")
    if host_command() is None:
        absent.append("planner-host on PATH, in a workspace or $NAV2_PYIF_PLANNER_HOST")
    return absent


def _ephemeral_start() -> int:
    try:
        return int(Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return 32768  # Linux's default when the range cannot be read


def free_port() -> int:
    """A loopback TCP port free now, below the kernel's ephemeral range: a copy of nav2_pyif's
    free_port (nav2_pyif.common.host_process), which this ROS Python does not import. A port
    the kernel hands out itself (Nav2's and Zenoh's own sockets) could be taken before the
    child binds it."""
    low, high = 20000, _ephemeral_start() - 1
    for _ in range(100):
        # a kernel range starting at or below 20000 leaves none below it: any free port
        port = random.randint(low, high) if high > low else 0
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return int(s.getsockname()[1])
    raise RuntimeError(f"no free TCP port on 127.0.0.1 in {low}..{high}")


_PRCTL = ctypes.CDLL(None, use_errno=True).prctl  # looked up here, not in the forked child
_PR_SET_PDEATHSIG = 1


def _end_with_the_test() -> None:
    """In a started child: SIGTERM it when the test process dies (Linux's parent-death
    signal). stop_all ends them by pid; this covers a test run that crashes or is killed
    first, whose children in their own sessions would otherwise live on (seen here: a
    planner host left serving after rclpy segfaulted the test process)."""
    _PRCTL(_PR_SET_PDEATHSIG, signal.SIGTERM)


class Processes:
    """Everything the test starts, each in its own process group, stopped by pid."""

    def __init__(self, logs: Path, env: dict[str, str]) -> None:
        self.logs, self.env = logs, env
        self.procs: dict[str, subprocess.Popen[bytes]] = {}

    def start(self, name: str, args: list[str], cwd: Path | None = None) -> None:
        log = open(self.logs / f"{name}.log", "ab")  # noqa: SIM115  (closed with the process)
        self.procs[name] = subprocess.Popen(
            args,
            stdout=log,
            stderr=subprocess.STDOUT,
            env=self.env,
            cwd=cwd,
            start_new_session=True,
            preexec_fn=_end_with_the_test,
        )

    def kill(self, name: str, sig: int = signal.SIGKILL) -> None:
        proc = self.procs.pop(name, None)
        if proc is None or proc.poll() is not None:
            return
        os.killpg(proc.pid, sig)
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(10)

    def alive(self, name: str) -> bool:
        proc = self.procs.get(name)
        return proc is not None and proc.poll() is None

    def log(self, name: str, lines: int = 40) -> str:
        path = self.logs / f"{name}.log"
        text = path.read_text(errors="replace").splitlines() if path.exists() else []
        return f"--- {name} ---\n" + "\n".join(text[-lines:])

    def logged_at(self, name: str, words: str, after: float) -> float | None:
        """Wall time of the first line of `name`'s log containing `words`, stamped at or after
        `after` (ROS log stamps for Nav2's servers, Python logging's for the planner host)."""
        path = self.logs / f"{name}.log"
        for line in path.read_text(errors="replace").splitlines() if path.exists() else []:
            if words not in line:
                continue
            ros, host = ROS_TIME.match(line), HOST_TIME.match(line)
            if ros:
                stamp = float(ros.group(1))
            elif host:
                stamp = datetime.strptime(host.group(1), "%Y-%m-%d %H:%M:%S,%f").timestamp()
            else:
                continue
            if stamp >= after:
                return stamp
        return None

    def stop_all(self) -> None:
        for name in list(self.procs):
            self.kill(name, signal.SIGINT)


def descendants(pid: int) -> set[int]:
    """Every process below ``pid``, from /proc."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(entry.name))
    found, stack = set(), [pid]
    while stack:
        for child in children.get(stack.pop(), []):
            found.add(child)
            stack.append(child)
    return found


def running(pid: int) -> bool:
    """Whether ``pid`` runs (exists and is no zombie)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def comm(pid: int) -> str:
    """The process's name (its first 15 characters), "" once it is gone."""
    try:
        return Path(f"/proc/{pid}/comm").read_text().strip()
    except OSError:
        return ""


def ctrl_c(
    launch: subprocess.Popen[bytes],
    grace: float = 10.0,
    sig: int = signal.SIGINT,
    wait: float = 60.0,
) -> tuple[int | None, dict[int, str]]:
    """SIGINT to the launch's process group, as a terminal's Ctrl-C (or ``sig``): the
    launch's exit code and what of every process below it still runs ``grace`` seconds after
    it exited; the code is None when the launch still runs ``wait`` seconds after the signal,
    and what is left is then what runs below it."""
    started = descendants(launch.pid)
    os.killpg(launch.pid, sig)
    try:
        code: int | None = launch.wait(wait)
    except subprocess.TimeoutExpired:
        return None, {p: comm(p) for p in started | {launch.pid} if running(p)}
    return code, left_after(started, grace)


def left_after(pids: Iterable[int], grace: float) -> dict[int, str]:
    """What of ``pids`` still runs once they all ended or ``grace`` seconds passed: pid, name."""
    watched = set(pids)
    deadline = time.monotonic() + grace
    while time.monotonic() < deadline and any(running(p) for p in watched):
        time.sleep(0.2)
    return {p: comm(p) for p in watched if running(p)}


SUCCEEDED, CANCELED, ABORTED = 4, 5, 6  # action_msgs/GoalStatus


def longest_stop(speeds: list[tuple[float, float]]) -> float:
    """The longest time [s] the robot stood still between the first and the last moment it
    moved, from (monotonic time, speed) samples (Nav2Client.speeds)."""
    moving = [t for t, v in speeds if v > 0.01]
    if len(moving) < 2:
        return 0.0
    return max(b - a for a, b in itertools.pairwise(moving))


def error_code(result: Any) -> int | None:
    """An action result's error code; None on Nav2 Humble, whose action results have none (the
    goal's status is all that tells a failure there)."""
    code = getattr(result, "error_code", None)
    return None if code is None else int(code)


def assert_error_code(result: Any, name: str, context: str = "") -> None:
    """``result`` (an action's result) carries the error code its type names ``name`` (e.g.
    "NO_VALID_CONTROL"), where the Nav2 has error codes (Jazzy on; not Humble)."""
    code = error_code(result)
    if code is not None:
        expected = getattr(type(result), name)
        assert code == expected, f"error code {code}, not {name} ({expected})\n{context}"


SERVERS = ("controller_server", "planner_server")
# Each Nav2 server a test may start, by the package whose lib/ holds it.
PACKAGES = {
    "controller_server": "nav2_controller",
    "planner_server": "nav2_planner",
    "smoother_server": "nav2_smoother",
    "behavior_server": "nav2_behaviors",
    "bt_navigator": "nav2_bt_navigator",
}


def start_nav2(procs: Processes, params: Path, servers: tuple[str, ...] = SERVERS) -> None:
    """Nav2's ``servers`` (controller_server, planner_server, smoother_server: each from its
    package) and a lifecycle manager (autostart) with `params`."""
    ros = ["--ros-args", "--params-file", str(params)]
    for server in servers:
        procs.start(server, [str(find(f"lib/{PACKAGES[server]}/{server}")), *ros])
    procs.start(
        "lifecycle_manager",
        [
            str(find("lib/nav2_lifecycle_manager/lifecycle_manager")),
            "--ros-args",
            "-r",
            "__node:=lifecycle_manager_navigation",
            "--params-file",
            str(params),
        ],
    )


def shared_router() -> str | None:
    """The endpoint of the Zenoh router ROS itself runs on (rmw_zenoh's, started by
    tests/test_nav2_launch.py's rmw_zenoh variant, listening on every interface), which the
    plugins and the host are to share; None when ROS runs on another RMW."""
    return os.environ.get("NAV2_PYIF_SHARED_ROUTER") or None


def plugin_zenoh(logs: Path, endpoint: str) -> str:
    """The params line that points a plugin at ``endpoint``: on zenoh-c
    ($NAV2_PYIF_ZENOH_BACKEND, set by tests/test_nav2_launch.py) ``zenoh_config``, the
    deployment guide's JSON5 file (docs/zenoh/plugin-client.json5, its endpoint replaced, written
    into ``logs``), as a ROS install would read it; on zenoh-pico ``zenoh_connect``."""
    if os.environ.get("NAV2_PYIF_ZENOH_BACKEND") != "zenoh-c":
        return f'zenoh_connect: ["{endpoint}"]'
    guide = HERE.parents[2] / "docs" / "zenoh" / "plugin-client.json5"
    config = logs / "plugin-client.json5"
    config.write_text(guide.read_text().replace("tcp/127.0.0.1:7447", endpoint))
    return f'zenoh_config: "{config}"'


def processes_in_own_domain(logs: Path, domain: int | None = None) -> Processes:
    """A process set in a ROS domain of its own: a random one this process's rclpy joins too,
    or ``domain``, for the processes only (the caller's own rclpy context joins it)."""
    if domain is None:  # this process's rclpy (its default context) joins the processes'
        os.environ["ROS_DOMAIN_ID"] = str(random.randint(100, 200))
        return Processes(logs, dict(os.environ, PYTHONUNBUFFERED="1"))
    # the caller's own rclpy context joins them (a second robot's stack)
    return Processes(logs, dict(os.environ, PYTHONUNBUFFERED="1", ROS_DOMAIN_ID=str(domain)))


def prepare(
    logs: Path, endpoint: str | None = None, domain: int | None = None
) -> tuple[str, Path, Processes]:
    """The plugins' endpoint (by default a free one, for the host to listen on), the test's
    Nav2 params naming it (in ``logs``), and the process set, in a ROS domain of its own: a
    random one this process's rclpy joins too, or ``domain``, for the processes only (the
    caller's own rclpy context joins it). On zenoh-c ($NAV2_PYIF_ZENOH_BACKEND, set by
    tests/test_nav2_launch.py) the plugins read the deployment guide's JSON5 file
    (docs/zenoh/plugin-client.json5, its endpoint replaced) through `zenoh_config`, as a ROS
    install would; zenoh-pico takes `zenoh_connect`."""
    endpoint = endpoint or f"tcp/127.0.0.1:{free_port()}"
    text = (HERE / "nav2_params.yaml").read_text()
    text = text.replace('zenoh_connect: ["@ENDPOINT@"]', plugin_zenoh(logs, endpoint))
    params = logs / "nav2_params.yaml"
    params.write_text(text.replace("@ENDPOINT@", endpoint))
    return endpoint, params, processes_in_own_domain(logs, domain)


# Nav2's own regulated pure pursuit: the C++ twin of the reference Python controller, which
# the native sides of the comparisons run.
NATIVE_PURE_PURSUIT = "nav2_regulated_pure_pursuit_controller::RegulatedPurePursuitController"
REFERENCE_PLANNERS = (
    *("--serve", f"{PREFIX}/FollowPath=nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"),
    *("--serve", f"{PREFIX}/GridBased=nav2_pyif_planners.astar:AStar"),
)
# Where the planner host runs and how it meets the plugins: given the process set and the
# plugins' endpoint, (a command prefix for the host, its Zenoh arguments). By default the
# host listens on the endpoint the plugins dial.
Topology = Callable[["Processes", str], tuple[list[str], list[str]]]


def direct(procs: Processes, endpoint: str) -> tuple[list[str], list[str]]:
    return [], ["--listen", endpoint]


def bring_up(
    logs: Path,
    robot_args: tuple[str, ...] = (),
    planners: tuple[str, ...] = REFERENCE_PLANNERS,
    edit_params: Callable[[str], str] = lambda text: text,
    topology: Topology = direct,
    endpoint: str | None = None,
    servers: tuple[str, ...] = SERVERS,
) -> Iterator[dict[str, Any]]:
    """What a launch test drives (a fixture's body): a planner host with ``planners`` (its
    arguments: by default the reference pure pursuit and A* on nav2_pyif/launch_test), the
    simulated robot (``robot_args``), controller_server, planner_server and a lifecycle
    manager with the test's params (through ``edit_params``; the plugins dial ``endpoint``,
    by default a free one the host listens on), and an rclpy client. ``servers``: the Nav2
    servers to start (the params' lifecycle manager must name the same). Skips, naming what is
    missing, without Nav2."""
    import pytest

    absent = missing()
    for server in servers:  # missing() checked the two every test starts
        if server not in SERVERS and find(f"lib/{PACKAGES[server]}/{server}") is None:
            absent.append(server)
    if absent:
        pytest.skip("the Nav2 launch test needs: " + ", ".join(absent))
    endpoint, params, procs = prepare(logs, endpoint)
    params.write_text(edit_params(params.read_text()))
    prefix, zenoh_args = topology(procs, endpoint)
    host = [*prefix, *(host_command() or []), *zenoh_args, *planners]

    def start_host() -> float:
        """Start the host; the wall time it was started at."""
        started = time.time()
        procs.start("planner_host", host)
        return started

    start_host()
    procs.start("sim_robot", ["python3", str(HERE / "sim_robot.py"), *robot_args])
    start_nav2(procs, params, servers)
    client = ros_client(procs)
    try:
        yield {
            "client": client,
            "procs": procs,
            "start_host": start_host,
            "logs": logs,
            "endpoint": endpoint,
        }
    finally:
        tear_down(client, procs)


def ros_client(procs: Processes, *first: str) -> Any:
    """The test's rclpy client (Nav2Client) in an rclpy context of its own, for tear_down to
    end. Its own context: on rmw_zenoh a context whose shutdown failed (its session's close
    timed out) refuses every later init, which failed each test after it with its processes
    left running. When rclpy cannot start, what ``procs`` started is stopped (``first`` by
    name, first) before the error is raised."""
    import rclpy

    context = rclpy.Context()
    try:
        rclpy.init(context=context)
        return Nav2Client(context)
    except BaseException:
        try:
            context.try_shutdown()
        finally:
            _stop(procs, first)
        raise


def tear_down(client: Any, procs: Processes, *first: str) -> None:
    """The test's rclpy client (from ros_client) and its context, then every process it
    started (``first`` by name, before the rest): the processes are stopped even when rclpy's
    own teardown raises (seen on rmw_zenoh, which left a failed test's Nav2 servers running)."""
    try:
        context = client.context
        client.destroy_node()
        context.try_shutdown()
    finally:
        _stop(procs, first)


def _stop(procs: Processes, first: tuple[str, ...]) -> None:
    for name in first:
        procs.kill(name, signal.SIGINT)
    procs.stop_all()


def Nav2Client(context: Any = None, name: str = "nav2_pyif_launch_test") -> Any:  # noqa: N802
    """The test's rclpy node ``name``, in ``context`` (another ROS domain: a second robot's
    Nav2) or rclpy's default one. (A factory: rclpy is imported only when present.)"""
    import rclpy
    from geometry_msgs.msg import PoseStamped
    from lifecycle_msgs.srv import GetState
    from nav2_msgs.action import ComputePathToPose, FollowPath, NavigateToPose, SmoothPath
    from nav_msgs.msg import Odometry
    from rclpy.action import ActionClient
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node

    class Client(Node):
        def __init__(self) -> None:
            super().__init__(name, context=context)
            # rclpy's global executor serves the default context only
            self.own_executor = None if context is None else SingleThreadedExecutor(context=context)
            self.plan_client = ActionClient(self, ComputePathToPose, "compute_path_to_pose")
            self.follow_client = ActionClient(self, FollowPath, "follow_path")
            self.smooth_client = ActionClient(self, SmoothPath, "smooth_path")
            self.navigate_client = ActionClient(self, NavigateToPose, "navigate_to_pose")
            # Service clients, each made once and kept for the node's life: a client destroyed
            # while its reply is still being delivered deadlocks rmw_zenoh's receiving thread
            # (ros2/rmw_zenoh#993), and no later reply or action reaches this process.
            self.kept_clients: dict[str, Any] = {}
            self.pose: tuple[float, float] | None = None
            self.speed = 0.0  # the commanded speed, as the simulated robot reports it
            self.speeds: list[tuple[float, float]] = []  # (monotonic time, speed), recorded
            self.recording = False
            self.recoveries = 0  # NavigateToPose feedback's number_of_recoveries, last seen
            self.messages_lost = 0  # incoming messages rclpy failed to take (spin_until)
            self.simulator_steps = 0  # the loopback simulator's steps, recorded (count_steps)
            self.create_subscription(Odometry, "odom", self._on_odom, 10)

        def count_steps(self, base_frame: str) -> None:
            """Count, while recording, the steps of Nav2's loopback simulator: each step it
            moves the robot by the command times its update_duration and broadcasts odom ->
            ``base_frame``, moving or not. A starved simulator steps less often than its
            period, so the robot's own time (steps x update_duration) is what the robot
            lived, whatever the machine's load did to the wall clock."""
            from tf2_msgs.msg import TFMessage

            def on_tf(msg: Any) -> None:
                if self.recording:
                    self.simulator_steps += sum(
                        t.child_frame_id == base_frame for t in msg.transforms
                    )

            # deep enough that a test process behind by seconds loses no step
            self.create_subscription(TFMessage, "/tf", on_tf, 1000)

        def _on_odom(self, msg: Any) -> None:
            self.pose = (msg.pose.pose.position.x, msg.pose.pose.position.y)
            self.speed = math.hypot(msg.twist.twist.linear.x, msg.twist.twist.angular.z)
            if self.recording:
                self.speeds.append((time.monotonic(), self.speed))

        def spin_until(self, done: Any, timeout: float) -> bool:
            end = time.monotonic() + timeout
            while time.monotonic() < end:
                if done():
                    return True
                try:
                    rclpy.spin_once(self, executor=self.own_executor, timeout_sec=0.05)
                except RuntimeError as exc:
                    # rclpy's take of one incoming message (odometry, action feedback) fails
                    # now and then over a long run ("Unable to convert call argument '0' to
                    # Python object", as in ros2/rclpy#848): that message is lost, the node
                    # goes on. Anything else is the test's failure.
                    if "Unable to convert call argument" not in str(exc):
                        raise
                    self.messages_lost += 1
            return bool(done())

        def wait(self, future: Any, timeout: float) -> Any:
            self.spin_until(future.done, timeout)
            return future.result() if future.done() else None

        def service_client(self, kind: Any, name: str) -> Any:
            """The client of the service ``name`` (of type ``kind``), made on first use."""
            if name not in self.kept_clients:
                self.kept_clients[name] = self.create_client(kind, name)
            return self.kept_clients[name]

        def state(self, node: str) -> str | None:
            client = self.service_client(GetState, f"/{node}/get_state")
            if not client.wait_for_service(timeout_sec=2.0):
                return None
            response = self.wait(client.call_async(GetState.Request()), 5.0)
            return response.current_state.label if response else None

        def wait_active(self, nodes: tuple[str, ...], timeout: float) -> dict[str, str | None]:
            end = time.monotonic() + timeout
            states: dict[str, str | None] = {}
            while time.monotonic() < end:
                states = {n: self.state(n) for n in nodes}
                if all(s == "active" for s in states.values()):
                    break
                time.sleep(0.5)
            return states

        def list_parameters(self, node: str, prefix: str) -> list[str]:
            from rcl_interfaces.srv import ListParameters

            client = self.service_client(ListParameters, f"/{node}/list_parameters")
            assert client.wait_for_service(timeout_sec=5.0)
            request = ListParameters.Request(prefixes=[prefix], depth=0)
            response = self.wait(client.call_async(request), 10.0)
            return list(response.result.names) if response else []

        def set_parameter(self, node: str, name: str, value: Any) -> tuple[bool, str]:
            """`ros2 param set`: (successful, reason)."""
            from rcl_interfaces.srv import SetParameters
            from rclpy.parameter import Parameter

            client = self.service_client(SetParameters, f"/{node}/set_parameters")
            assert client.wait_for_service(timeout_sec=5.0)
            request = SetParameters.Request(
                parameters=[Parameter(name, value=value).to_parameter_msg()]
            )
            response = self.wait(client.call_async(request), 15.0)
            assert response is not None, f"no answer to set_parameters {name}"
            result = response.results[0]
            return bool(result.successful), str(result.reason)

        def plan(
            self,
            x: float,
            y: float,
            timeout: float = 30.0,
            viapoints: list[tuple[float, float]] = (),  # type: ignore[assignment]
        ) -> Any:
            """ComputePathToPose from the robot to (x, y) in the map frame, through
            ``viapoints`` (Lyrical's goal field): the action's result, or None."""
            assert self.plan_client.wait_for_server(timeout_sec=10.0)
            goal = ComputePathToPose.Goal()
            goal.goal = PoseStamped()
            goal.goal.header.frame_id = "map"
            goal.goal.pose.position.x, goal.goal.pose.position.y = x, y
            goal.goal.pose.orientation.w = 1.0
            goal.use_start = False
            for vx, vy in viapoints:
                via = PoseStamped()
                via.header.frame_id = "map"
                via.pose.position.x, via.pose.position.y = vx, vy
                via.pose.orientation.w = 1.0
                goal.viapoints.append(via)
            handle = self.wait(self.plan_client.send_goal_async(goal), 10.0)
            assert handle is not None and handle.accepted, "ComputePathToPose not accepted"
            return self.wait(handle.get_result_async(), timeout)

        def smooth(self, path: Any, smoother: str, timeout: float = 30.0) -> Any:
            """SmoothPath (smoother_server): the action's result, or None."""
            assert self.smooth_client.wait_for_server(timeout_sec=10.0)
            goal = SmoothPath.Goal()
            goal.path = path
            goal.smoother_id = smoother
            goal.max_smoothing_duration.sec = 2
            goal.check_for_collisions = False
            handle = self.wait(self.smooth_client.send_goal_async(goal), 10.0)
            assert handle is not None and handle.accepted, "SmoothPath not accepted"
            return self.wait(handle.get_result_async(), timeout)

        def navigate(self, x: float, y: float, behavior_tree: str = "") -> Any:
            """NavigateToPose (bt_navigator, its default BT or the ``behavior_tree`` file): the
            goal handle. Feedback updates ``recoveries``; the odometry's speeds are recorded
            from now on."""
            assert self.navigate_client.wait_for_server(timeout_sec=10.0)
            goal = NavigateToPose.Goal()
            goal.behavior_tree = behavior_tree
            goal.pose.header.frame_id = "map"
            goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
            goal.pose.pose.orientation.w = 1.0
            self.recoveries, self.speeds, self.recording = 0, [], True
            self.simulator_steps = 0

            def on_feedback(message: Any) -> None:
                self.recoveries = int(message.feedback.number_of_recoveries)

            sent = self.navigate_client.send_goal_async(goal, feedback_callback=on_feedback)
            handle = self.wait(sent, 10.0)
            assert handle is not None and handle.accepted, "NavigateToPose not accepted"
            return handle

        def send_follow(
            self,
            path: Any,
            goal_checker: str = "general_goal_checker",
            controller: str = "FollowPath",
        ) -> Any:
            """FollowPath sent: the future of its goal handle."""
            assert self.follow_client.wait_for_server(timeout_sec=10.0)
            goal = FollowPath.Goal()
            goal.path = path
            goal.controller_id = controller
            goal.goal_checker_id = goal_checker
            return self.follow_client.send_goal_async(goal)

        def follow(self, path: Any, goal_checker: str = "general_goal_checker") -> Any:
            handle = self.wait(self.send_follow(path, goal_checker), 10.0)
            assert handle is not None and handle.accepted, "FollowPath not accepted"
            return handle

    return Client()
