"""The documented launch file, run as the README says: ``ros2 launch nav2_pyif_bridge
nav2_pyif.launch.py`` (with this test's params and endpoint) brings up the planner host,
controller_server, planner_server and the lifecycle manager; a goal is reached; Ctrl-C (SIGINT
to the launch's process group, as a terminal sends it) ends every process it started. And
with no params_file, the package's own params file alone configures every server.

Needs what test_nav2_pyif.py needs, plus `ros2 launch` (ros2cli, launch, launch_ros). Skipped,
saying what is missing, otherwise.
"""

from __future__ import annotations

import math
import os
import shutil
import time
from pathlib import Path

import nav2_testing
import pytest

HERE = Path(__file__).resolve().parent
PREFIX = nav2_testing.PREFIX
GOAL = (2.0, 0.5)
#: The host the launch file is given; without it, the launch file's own choice (nav2_pyif's
#: planner-host from the install space, else the one on PATH) is tested.
CHOSEN_HOST = os.environ.get("NAV2_PYIF_PLANNER_HOST")
DIED = "process has died"  # what `ros2 launch` logs when one of its processes ends


def _launch_missing() -> list[str]:
    absent = []
    if shutil.which("ros2") is None:
        absent.append("the ros2 command (ros2cli)")
    try:
        import launch  # noqa: F401
        import launch_ros  # noqa: F401
    except ImportError:
        absent.append("launch and launch_ros")
    host = nav2_testing.host_command()
    if CHOSEN_HOST and host is not None and len(host) != 1:
        absent.append("$NAV2_PYIF_PLANNER_HOST as one executable (the launch file's argument)")
    return absent


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
    except OSError:
        return ""


def test_the_launch_file_reaches_a_goal_and_ctrl_c_ends_everything(tmp_path: Path) -> None:
    missing = nav2_testing.missing() + _launch_missing()
    if missing:
        pytest.skip("the launch-file test needs: " + ", ".join(missing))
    endpoint, params, procs = nav2_testing.prepare(tmp_path)
    host_argument = [f"planner_host:={CHOSEN_HOST}"] if CHOSEN_HOST else []
    installed = None if CHOSEN_HOST else nav2_testing.find("lib/nav2_pyif/planner-host")
    procs.start("sim_robot", ["python3", str(HERE / "sim_robot.py")])
    procs.start(
        "launch",
        [
            "ros2",
            "launch",
            "nav2_pyif_bridge",
            "nav2_pyif.launch.py",
            f"params_file:={params}",
            f"listen:={endpoint}",
            f"key_prefix:={PREFIX}",
            *host_argument,
        ],
    )
    launch = procs.procs["launch"]
    client = nav2_testing.ros_client(procs)
    try:
        states = client.wait_active(nav2_testing.SERVERS, 120.0)
        assert all(s == "active" for s in states.values()), f"{states}\n{procs.log('launch')}"
        planned = client.plan(*GOAL)
        assert planned is not None and planned.status == nav2_testing.SUCCEEDED, procs.log("launch")
        handle = client.follow(planned.result.path)
        result = client.wait(handle.get_result_async(), 90.0)
        assert result is not None and result.status == nav2_testing.SUCCEEDED, procs.log("launch")
        assert client.spin_until(lambda: client.pose is not None, 5.0)
        x, y = client.pose
        assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL}"

        started = nav2_testing.descendants(launch.pid)
        names = {nav2_testing.comm(p) for p in started if nav2_testing.running(p)}
        assert {"controller_serv", "planner_server"} <= names, names  # comm: 15 characters
        if installed is not None:  # a workspace's: the host runs from its install space
            commands = [_cmdline(p) for p in started if nav2_testing.running(p)]
            assert any(str(installed) in c for c in commands), commands
        code, left = nav2_testing.ctrl_c(launch)  # Ctrl-C in the launch's terminal
        assert not left, f"still running after Ctrl-C: {left}\n{procs.log('launch')}"
        assert code == 0, f"ros2 launch exited {code}\n{procs.log('launch')}"
    finally:
        nav2_testing.tear_down(client, procs)


def test_the_launch_file_with_its_own_params_configures_every_server(tmp_path: Path) -> None:
    """No params_file: the launch passes the package's params/nav2_pyif_params.yaml alone, as a
    new user's first try does. Every server configures (a costmap layer listed without its
    plugin once crashed controller_server here), and nothing the launch started dies."""
    missing = nav2_testing.missing() + _launch_missing()
    if missing:
        pytest.skip("the launch-file test needs: " + ", ".join(missing))
    endpoint, _, procs = nav2_testing.prepare(tmp_path)
    host_argument = [f"planner_host:={CHOSEN_HOST}"] if CHOSEN_HOST else []
    procs.start("sim_robot", ["python3", str(HERE / "sim_robot.py")])
    procs.start(
        "launch",
        ["ros2", "launch", "nav2_pyif_bridge", "nav2_pyif.launch.py", f"listen:={endpoint}",
         *host_argument],
    )  # fmt: skip
    client = nav2_testing.ros_client(procs)
    try:
        configured = ("inactive", "active")
        deadline = time.monotonic() + 90.0
        states = client.wait_active(nav2_testing.SERVERS, 1.0)
        while time.monotonic() < deadline and not all(s in configured for s in states.values()):
            assert DIED not in procs.log("launch", 100_000), procs.log("launch")
            states = client.wait_active(nav2_testing.SERVERS, 1.0)
        assert all(s in configured for s in states.values()), f"{states}\n{procs.log('launch')}"
        assert DIED not in procs.log("launch", 100_000), procs.log("launch")
        _, left = nav2_testing.ctrl_c(procs.procs["launch"])
        assert not left, f"still running after Ctrl-C: {left}\n{procs.log('launch')}"
    finally:
        nav2_testing.tear_down(client, procs)
