"""The launch test of issue 4: Nav2's controller_server and planner_server with the nav2_pyif
plugins, a lifecycle manager, a real planner host and a small simulated robot.

1. ComputePathToPose (Python A*) and FollowPath (Python regulated pure pursuit): the robot
   reaches the goal around a wall;
2. the host is killed (SIGKILL) mid-goal: the goal aborts with the matching error code and
   both servers stay active;
3. the host is restarted: the next goal succeeds (the plugins re-send their state).

Needs a sourced ROS 2 (rclpy, nav2_msgs) with Nav2's controller_server, planner_server and
lifecycle_manager, this package built and sourced (its pluginlib index), and a planner host:
`planner-host` on PATH or $NAV2_PYIF_PLANNER_HOST (a command, e.g. a wrapper that activates
the nav2_pyif venv). Skipped, saying what is missing, otherwise:

    source /opt/ros/jazzy/setup.bash && source install/setup.bash
    python -m pytest bridge_plugin/test/nav2 -v
"""

from __future__ import annotations

import math
import os
import random
import shlex
import shutil
import signal
import socket
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

HERE = Path(__file__).resolve().parent
PREFIX = "nav2_pyif/launch_test"
GOAL_A = (2.0, 0.5)  # behind the wall: the plan goes around it
GOAL_B = (0.0, 0.0)


def _prefixes() -> list[Path]:
    return [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]


def _find(relative: str) -> Path | None:
    for prefix in _prefixes():
        if (prefix / relative).exists():
            return prefix / relative
    return None


def _host_command() -> list[str] | None:
    command = os.environ.get("NAV2_PYIF_PLANNER_HOST")
    if command:
        return shlex.split(command)
    found = shutil.which("planner-host")
    return [found] if found else None


def _missing() -> list[str]:
    missing = []
    try:
        import nav2_msgs.action  # noqa: F401
        import rclpy  # noqa: F401
    except ImportError:
        missing.append("a sourced ROS 2 with rclpy and nav2_msgs")
    for exe in (
        "lib/nav2_controller/controller_server",
        "lib/nav2_planner/planner_server",
        "lib/nav2_lifecycle_manager/lifecycle_manager",
    ):
        if _find(exe) is None:
            missing.append(exe.rsplit("/", 1)[-1])
    if (
        _find("share/ament_index/resource_index/nav2_core__pluginlib__plugin/nav2_pyif_bridge")
        is None
    ):
        missing.append("nav2_pyif_bridge built and sourced")
    if _host_command() is None:
        missing.append("planner-host on PATH or $NAV2_PYIF_PLANNER_HOST")
    return missing


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


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

    def stop_all(self) -> None:
        for name in list(self.procs):
            self.kill(name, signal.SIGINT)


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    missing = _missing()
    if missing:
        pytest.skip("the Nav2 launch test needs: " + ", ".join(missing))
    logs = tmp_path_factory.mktemp("nav2_launch_test")
    endpoint = f"tcp/127.0.0.1:{_free_port()}"
    params = logs / "nav2_params.yaml"
    params.write_text((HERE / "nav2_params.yaml").read_text().replace("@ENDPOINT@", endpoint))
    domain = str(random.randint(100, 200))
    os.environ["ROS_DOMAIN_ID"] = domain  # this process's rclpy too
    env = dict(os.environ, ROS_DOMAIN_ID=domain, PYTHONUNBUFFERED="1")
    procs = Processes(logs, env)
    host = [
        *(_host_command() or []),
        "--listen",
        endpoint,
        "--serve",
        f"{PREFIX}/FollowPath=nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
        "--serve",
        f"{PREFIX}/GridBased=nav2_pyif_planners.astar:AStar",
    ]
    ros = ["--ros-args", "--params-file", str(params)]

    def start_host() -> None:
        procs.start("planner_host", host)

    start_host()
    procs.start("sim_robot", ["python3", str(HERE / "sim_robot.py")])
    procs.start("controller_server", [str(_find("lib/nav2_controller/controller_server")), *ros])
    procs.start("planner_server", [str(_find("lib/nav2_planner/planner_server")), *ros])
    procs.start(
        "lifecycle_manager",
        [
            str(_find("lib/nav2_lifecycle_manager/lifecycle_manager")),
            "--ros-args",
            "-r",
            "__node:=lifecycle_manager_navigation",
            "--params-file",
            str(params),
        ],
    )
    import rclpy

    rclpy.init()
    client = Nav2Client()
    try:
        yield {"client": client, "procs": procs, "start_host": start_host, "logs": logs}
    finally:
        client.destroy_node()
        rclpy.try_shutdown()
        procs.stop_all()


def Nav2Client() -> Any:  # noqa: N802  (a factory: rclpy is imported only when present)
    import rclpy
    from geometry_msgs.msg import PoseStamped
    from lifecycle_msgs.srv import GetState
    from nav2_msgs.action import ComputePathToPose, FollowPath
    from nav_msgs.msg import Odometry
    from rclpy.action import ActionClient
    from rclpy.node import Node

    class Client(Node):
        def __init__(self) -> None:
            super().__init__("nav2_pyif_launch_test")
            self.plan_client = ActionClient(self, ComputePathToPose, "compute_path_to_pose")
            self.follow_client = ActionClient(self, FollowPath, "follow_path")
            self.pose: tuple[float, float] | None = None
            self.create_subscription(Odometry, "odom", self._on_odom, 10)

        def _on_odom(self, msg: Any) -> None:
            self.pose = (msg.pose.pose.position.x, msg.pose.pose.position.y)

        def spin_until(self, done: Any, timeout: float) -> bool:
            end = time.monotonic() + timeout
            while time.monotonic() < end:
                if done():
                    return True
                rclpy.spin_once(self, timeout_sec=0.05)
            return bool(done())

        def wait(self, future: Any, timeout: float) -> Any:
            self.spin_until(future.done, timeout)
            return future.result() if future.done() else None

        def state(self, node: str) -> str | None:
            client = self.create_client(GetState, f"/{node}/get_state")
            try:
                if not client.wait_for_service(timeout_sec=2.0):
                    return None
                response = self.wait(client.call_async(GetState.Request()), 5.0)
                return response.current_state.label if response else None
            finally:
                self.destroy_client(client)

        def wait_active(self, nodes: tuple[str, ...], timeout: float) -> dict[str, str | None]:
            end = time.monotonic() + timeout
            states: dict[str, str | None] = {}
            while time.monotonic() < end:
                states = {n: self.state(n) for n in nodes}
                if all(s == "active" for s in states.values()):
                    break
                time.sleep(0.5)
            return states

        def plan(self, x: float, y: float, timeout: float = 30.0) -> Any:
            assert self.plan_client.wait_for_server(timeout_sec=10.0)
            goal = ComputePathToPose.Goal()
            goal.goal = PoseStamped()
            goal.goal.header.frame_id = "map"
            goal.goal.pose.position.x, goal.goal.pose.position.y = x, y
            goal.goal.pose.orientation.w = 1.0
            goal.use_start = False
            handle = self.wait(self.plan_client.send_goal_async(goal), 10.0)
            assert handle is not None and handle.accepted, "ComputePathToPose not accepted"
            return self.wait(handle.get_result_async(), timeout)

        def follow(self, path: Any) -> Any:
            assert self.follow_client.wait_for_server(timeout_sec=10.0)
            goal = FollowPath.Goal()
            goal.path = path
            goal.controller_id = "FollowPath"
            goal.goal_checker_id = "general_goal_checker"
            handle = self.wait(self.follow_client.send_goal_async(goal), 10.0)
            assert handle is not None and handle.accepted, "FollowPath not accepted"
            return handle

    return Client()


SUCCEEDED, ABORTED = 4, 6  # action_msgs/GoalStatus


def _drive_to(nav2: dict[str, Any], goal: tuple[float, float]) -> Any:
    client, procs = nav2["client"], nav2["procs"]
    planned = client.plan(*goal)
    logs = "\n".join(procs.log(n) for n in ("planner_server", "planner_host"))
    assert planned is not None, "no ComputePathToPose result\n" + logs
    assert planned.status == SUCCEEDED, f"planning failed: {planned.result.error_code}\n{logs}"
    path = planned.result.path
    assert len(path.poses) > 10 and path.header.frame_id == "map"
    return path


def test_reaches_the_goal_survives_a_host_crash_and_recovers(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    servers = ("controller_server", "planner_server")
    states = client.wait_active(servers, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + "\n".join(
        procs.log(n) for n in (*servers, "lifecycle_manager", "planner_host")
    )

    # 1. plan around the wall and follow the plan to the goal
    path = _drive_to(nav2, GOAL_A)
    assert min(p.pose.position.y for p in path.poses) < -0.6, "the plan does not avoid the wall"
    handle = client.follow(path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    assert client.spin_until(lambda: client.pose is not None, 5.0)
    x, y = client.pose
    assert math.hypot(x - GOAL_A[0], y - GOAL_A[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL_A}"

    # 2. the host dies mid-goal: the goal aborts with the plugin's error code, Nav2 stays up
    handle = client.follow(_drive_to(nav2, GOAL_B))
    client.spin_until(lambda: False, 1.5)  # driving
    procs.kill("planner_host", signal.SIGKILL)
    killed = time.monotonic()
    result = client.wait(handle.get_result_async(), 30.0)
    logs = procs.log("controller_server")
    assert result is not None and result.status == ABORTED, f"FollowPath: {result}\n{logs}"
    from nav2_msgs.action import FollowPath

    # No reply in time (ControllerTimedOut) while the dead host's token lingers, or no host
    # alive (ControllerException -> UNKNOWN) once it is gone.
    codes = {FollowPath.Result.CONTROLLER_TIMED_OUT, FollowPath.Result.UNKNOWN}
    assert result.result.error_code in codes, f"error code {result.result.error_code}\n{logs}"
    assert time.monotonic() - killed < 5.0, "the abort took longer than a few timeouts"
    assert client.wait_active(servers, 10.0) == dict.fromkeys(servers, "active")
    assert procs.alive("controller_server") and procs.alive("planner_server")

    # 3. a new host: the next goal succeeds
    nav2["start_host"]()
    deadline = time.monotonic() + 60.0
    planned = None
    while time.monotonic() < deadline:  # until the plugin sees the new host
        planned = client.plan(*GOAL_B)
        if planned is not None and planned.status == SUCCEEDED:
            break
        client.spin_until(lambda: False, 1.0)
    assert planned is not None and planned.status == SUCCEEDED, procs.log("planner_server")
    handle = client.follow(planned.result.path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL_B[0], y - GOAL_B[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL_B}"
