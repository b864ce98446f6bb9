"""The planner host in containers (docker/), run with podman: the image built from
docker/Dockerfile on a locally made base, a controller session driven into it from outside
through the reference client, the container killed mid-session and restarted; and
docker/compose.yaml brought up as written (router + host serving the mounted planner
directory), its host crashed and restarted by the restart policy. Skipped, saying why, only
where this machine cannot run podman."""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import socket
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif import Plan
from nav2_pyif.client import ControllerClient, GlobalPlannerClient, Timeouts

from tests.conftest import FIXTURES, child_pids, free_port, make_costmap, wait_until
from tests.podman.support import (
    IMAGE,
    LOCAL_BASE,
    ROOT,
    Unavailable,
    base_image,
    build_image,
    exclusive,
    podman,
    podman_env,
    probe,
    remove_stale_images,
    require_podman,
    stale_images,
)
from tests.test_host_e2e import pose

# The first run makes a base image and builds.
pytestmark = [pytest.mark.container, pytest.mark.timeout(900)]
KEY = "nav2_pyif/container/FollowPath"
# Generous: the first calls into a fresh container import NumPy and rclpy in its worker.
TIMEOUTS = Timeouts(call=5.0, lifecycle=10.0, configure=20.0, plan=20.0)


@pytest.fixture(scope="module")
def image() -> Iterator[tuple[str, str]]:
    """(planner-host image, base image), this checkout's container tests holding the lock."""
    with contextlib.ExitStack() as stack:
        try:
            require_podman()
            stack.enter_context(exclusive())
            base = base_image()
            probe(base)
        except Unavailable as exc:
            pytest.skip(f"container test skipped: {exc}")
        yield build_image(base), base
        remove_stale_images()


def test_one_image_is_left_whatever_the_checkout(image: tuple[str, str]) -> None:
    """The tag names no checkout path (one per path left ~0.4 GB each), and neither the
    image a build replaced nor any build layer is left behind untagged."""
    assert image[0] == IMAGE and image[0].endswith(":test")
    assert str(ROOT) not in IMAGE and ROOT.name not in IMAGE
    assert not stale_images()
    guide = (ROOT / "python" / "doc" / "howto" / "contributing.md").read_text()
    assert IMAGE in guide and LOCAL_BASE.split(":")[0] in guide  # says what is left


def _logs(name: str) -> str:
    return podman("logs", name, check=False).stdout + podman("logs", name, check=False).stderr


def test_host_container_recovers_after_being_killed(
    image: tuple[str, str], zsession_factory: Any
) -> None:
    port, name = free_port(), f"nav2-pyif-test-{os.getpid()}"
    podman(
        "run", "--detach", "--init", "--name", name, "--publish", f"127.0.0.1:{port}:7447",
        "--env", "NAV2_PYIF_LISTEN=tcp/0.0.0.0:7447",
        "--env", f"NAV2_PYIF_KEY={KEY}",
        "--env", "NAV2_PYIF_PLANNER=echo_planners:EchoController",
        "--volume", f"{FIXTURES}:/planners:ro",
        image[0],
    )  # fmt: skip
    try:
        client = ControllerClient(
            zsession_factory(f"tcp/127.0.0.1:{port}"), KEY, make_costmap(),
            params={"gain": 4.0}, timeouts=TIMEOUTS,
        )  # fmt: skip
        assert client.wait_for_host(60), _logs(name)
        assert client.configure() == {"gain": 4.0, "label": "echo"}
        client.activate()
        client.set_plan(Plan(np.zeros((17, 3)), "odom"))
        client.set_speed_limit(30.0, True)
        client.set_parameters({"gain": 6.0})
        assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == 17.0

        podman("kill", "--signal", "KILL", name)  # the whole container, mid-session
        assert client.hosts.wait_for(lambda alive: not alive, 20), "host still looks alive"
        with pytest.raises(api.ControllerException, match="no planner host is alive"):
            client.compute_velocity_commands(pose(), Twist())

        podman("start", name)
        assert client.wait_for_host(60), _logs(name)
        cmd = client.compute_velocity_commands(pose(), Twist())
        assert (cmd.twist.linear.x, cmd.twist.linear.y, cmd.twist.linear.z) == (17.0, 6.0, 30.0)
        assert client.resyncs == 1 and client.epoch == 2  # plan, params, limit re-sent once

        started = time.monotonic()
        podman("stop", "--time", "20", name)  # SIGTERM: the host must exit by itself
        assert time.monotonic() - started < 10
        exit_code = podman("inspect", "--format", "{{.State.ExitCode}}", name).stdout.strip()
        assert exit_code == "143", _logs(name)  # ended by SIGTERM, cleanly
    finally:
        podman("rm", "--force", name, check=False)


def _compose(project: str, env: dict[str, str], *args: str, check: bool = True) -> str:
    result = subprocess.run(
        ["podman-compose", "-p", project, "-f", str(ROOT / "docker/compose.yaml"), *args],
        capture_output=True, text=True, timeout=300, env=env,
    )  # fmt: skip
    if check:
        assert result.returncode == 0, f"podman-compose {args}: {result.stdout}\n{result.stderr}"
    return result.stdout


def test_compose_router_and_host_serve_the_mounted_planners(
    image: tuple[str, str], zsession_factory: Any
) -> None:
    if shutil.which("podman-compose") is None:
        pytest.skip("compose test skipped: podman-compose is not installed (nav2-pyif[dev])")
    if not Path("/usr/lib/cni/dnsname").exists():
        pytest.skip("compose test skipped: the CNI dnsname plugin (service names) is missing")
    port, project = free_port(), f"nav2pyif{os.getpid()}"
    env = podman_env(NAV2_PYIF_IMAGE=image[0], BASE_IMAGE=image[1], NAV2_PYIF_ROUTER_PORT=str(port))
    try:
        _compose(project, env, "up", "--detach")
        # `up --detach` returns before the router listens (slower on a loaded machine)
        assert wait_until(lambda: _accepts(port), 60), _logs(f"{project}_router_1")
        # The robot's side, as the C++ plugin connects: a Zenoh client of the router.
        session = zsession_factory(f"tcp/127.0.0.1:{port}", mode="client")
        controller = ControllerClient(
            session, "nav2_pyif/robot1/FollowPath", make_costmap(), timeouts=TIMEOUTS
        )
        planner = GlobalPlannerClient(
            session, "nav2_pyif/robot1/GridBased", make_costmap(), timeouts=TIMEOUTS
        )
        assert controller.wait_for_host(60) and planner.wait_for_host(60), _logs(
            f"{project}_planner-host_1"
        )
        declared = controller.configure()  # docker/planners/go_to.py
        assert declared == {"speed": 0.3, "lookahead": 0.4}
        planner.configure()
        controller.activate()
        planner.activate()
        plan = planner.create_plan(pose(0.5, 0.5), pose(3.5, 0.5))  # A* from the image
        assert len(plan) > 10 and np.allclose(plan.xy_yaw[-1, :2], [3.5, 0.5], atol=0.1)
        controller.set_plan(plan)
        cmd = controller.compute_velocity_commands(pose(0.5, 0.5), Twist())
        # GoTo: 0.3 m/s scaled by the cosine of the heading error to its carrot on the plan
        before = (cmd.twist.linear.x, cmd.twist.angular.z)
        assert 0.25 < before[0] <= 0.3

        # Crash the host process from outside: the restart policy brings the container back.
        container = f"{project}_planner-host_1"
        pid = podman("inspect", "--format", "{{.State.Pid}}", container).stdout.strip()
        children = child_pids(int(pid))  # the host under the container's init
        assert children, f"no process under the container's init {pid}"
        for child in children:
            os.kill(child, signal.SIGKILL)
        assert controller.hosts.wait_for(lambda alive: not alive, 20)
        assert controller.wait_for_host(60), _logs(container)
        cmd = controller.compute_velocity_commands(pose(0.5, 0.5), Twist())
        # the plan restored: no NoValidControl, and the same command from the same plan
        assert (cmd.twist.linear.x, cmd.twist.angular.z) == pytest.approx(before)
        assert controller.resyncs == 1
        restarts = podman("inspect", "--format", "{{.RestartCount}}", container).stdout
        assert restarts.strip() == "1"
    finally:
        _compose(project, env, "down", check=False)


def _accepts(port: int) -> bool:
    """Whether something listens on 127.0.0.1:port (the compose router's published port)."""
    with socket.socket() as probe:
        probe.settimeout(1.0)
        return probe.connect_ex(("127.0.0.1", port)) == 0
