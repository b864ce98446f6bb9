"""The function-delegate configuration in Nav2: no planner host started by hand. The controller's
YAML names only `python_module` (the APF controller of nav2_pyif_planners.apf: plain functions
named after the roles, so no `python_delegates` is needed) and the planner's
`python_planner`; each plugin starts
its own `planner-host --respawn`, the robot reaches the goal, and the hosts end with Nav2.

Needs what test_nav2_pyif.py needs; the planner host command must be one executable here
(`planner_host_command`): `planner-host` on PATH or $NAV2_PYIF_PLANNER_HOST.
"""

from __future__ import annotations

import math
import os
import random
import time
from pathlib import Path

import nav2_testing
import pytest

HERE = Path(__file__).resolve().parent
GOAL = (2.0, 0.5)


def seed_params(host: str) -> str:
    """The launch test's params with the plugins' key and endpoint set to function delegates."""
    out = []
    for line in (HERE / "nav2_params.yaml").read_text().splitlines():
        stripped = line.strip()
        indent = line[: len(line) - len(line.lstrip())]
        if stripped.startswith("zenoh_connect:"):
            continue
        if stripped.startswith('key: "nav2_pyif/launch_test/FollowPath"'):
            out += [
                f'{indent}python_module: "nav2_pyif_planners.apf"',
                f'{indent}planner_host_command: "{host}"',
            ]
        elif stripped.startswith('key: "nav2_pyif/launch_test/GridBased"'):
            out += [
                f'{indent}python_planner: "nav2_pyif_planners.astar:AStar"',
                f'{indent}planner_host_command: "{host}"',
            ]
        else:
            out.append(line)
    return "\n".join(out) + "\n"


def local_hosts() -> list[int]:
    """Pids of the planner hosts the plugins started (their key names the server node)."""
    pids = []
    for proc in Path("/proc").iterdir():
        try:
            cmdline = (proc / "cmdline").read_bytes().replace(b"\0", b" ")
        except (OSError, ValueError):
            continue
        if b"nav2_pyif/local/controller_server/FollowPath" in cmdline and b"--listen" in cmdline:
            stat = (proc / "stat").read_text()
            if stat.rsplit(")", 1)[-1].split()[0] != "Z":
                pids.append(int(proc.name))
    return pids


def test_seed_style_yaml_starts_its_own_host(tmp_path: Path) -> None:
    missing = nav2_testing.missing()
    host = nav2_testing.host_command()
    if host is not None and len(host) != 1:
        missing.append("$NAV2_PYIF_PLANNER_HOST as one executable (planner_host_command)")
    if missing:
        pytest.skip("the Nav2 launch test needs: " + ", ".join(missing))
    assert host is not None
    params = tmp_path / "nav2_params.yaml"
    params.write_text(seed_params(host[0]))
    domain = str(random.randint(100, 200))
    os.environ["ROS_DOMAIN_ID"] = domain
    env = dict(os.environ, ROS_DOMAIN_ID=domain, PYTHONUNBUFFERED="1")
    procs = nav2_testing.Processes(tmp_path, env)
    procs.start("sim_robot", ["python3", str(HERE / "sim_robot.py")])
    nav2_testing.start_nav2(procs, params)
    client = nav2_testing.ros_client(procs, "lifecycle_manager", *nav2_testing.SERVERS)
    try:
        states = client.wait_active(nav2_testing.SERVERS, 120.0)
        logs = "\n".join(procs.log(n) for n in (*nav2_testing.SERVERS, "lifecycle_manager"))
        assert all(s == "active" for s in states.values()), f"{states}\n{logs}"
        assert local_hosts(), "no planner host started by the controller plugin\n" + logs

        planned = client.plan(*GOAL)
        assert planned is not None and planned.status == nav2_testing.SUCCEEDED, logs
        handle = client.follow(planned.result.path)
        result = client.wait(handle.get_result_async(), 90.0)
        logs = procs.log("controller_server", 80)
        assert result is not None and result.status == nav2_testing.SUCCEEDED, f"{result}\n{logs}"
        x, y = client.pose
        assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL}"
    finally:
        nav2_testing.tear_down(client, procs, "lifecycle_manager", *nav2_testing.SERVERS)
    end = time.monotonic() + 15.0
    while local_hosts() and time.monotonic() < end:
        time.sleep(0.2)
    assert not local_hosts(), "the plugin's planner host outlived Nav2"
