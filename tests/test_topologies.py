"""Every documented topology with every tool, over real processes (the deployment guide, "Which
tool works where"). One planner host per deployment, shared by the topology's tests, serving
the keys ``nav2-pyif sim --connect`` drives (pure pursuit, A*), remote reloads allowed.

Topologies, as the tools see them:

- ``direct``: the host listens (``--listen``, DEPLOYMENT §1); tools are clients of it.
- ``router``: ``nav2-pyif router``; the host joins it (``--connect``, §2); tools are clients.
- ``peer``: the listening host of ``direct``, tools as Zenoh peers connecting to it.
- ``gossip``: the router of ``router``, tools as peers connecting to it (rmw_zenoh's nodes):
  they learn the host's own endpoint through the router and reach it directly.
- ``netns``: the host on another machine (a network namespace behind a veth link) joining a
  router on this one (§2, §4); tools are clients of the router. Skipped, saying why, where
  namespaces cannot be made.

Tools: the reference client (the C++ plugin's Python twin), ``nav2-pyif reload``,
``nav2-pyif sim --connect`` (a client, as the plugin: not in the peer rows) and
``nav2-pyif hosts``. No ``nav2-pyif-bench`` command targets a running host (each starts its
own peers), so none is here. Then what the tools say when there is no host on their key or
no router at all, and the README's router sequence started in quick succession."""

from __future__ import annotations

import contextlib
import json
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
import yaml
from geometry_msgs.msg import Twist
from nav2_pyif.client import ControllerClient, GlobalPlannerClient
from nav2_pyif.common.zenoh_config import connect_to

from tests.conftest import free_port, make_costmap, wait_until
from tests.conftest import nav2_pyif_tool as tool
from tests.netns import SUBNET, namespace_link
from tests.test_env_and_router import start_router
from tests.test_host_e2e import GENEROUS, pose
from tests.test_network import start_remote_host, stop

pytestmark = pytest.mark.integration

CONTROLLER_KEY = "nav2_pyif/sim/FollowPath"  # what nav2-pyif sim --connect drives
PLANNER_KEY = "nav2_pyif/sim/GridBased"
CONTROLLER = "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"
PLANNERS = {
    "planners": [
        {"key": CONTROLLER_KEY, "planner": CONTROLLER},
        {"key": PLANNER_KEY, "planner": "nav2_pyif_planners.astar:AStar"},
    ]
}
HOST_ARGS = ("--allow-remote-reload", "--log-level", "INFO")
READY = " ready ("
TOPOLOGIES = ["direct", "router", "peer", "gossip", "netns"]
CLIENT_TOPOLOGIES = ["direct", "router", "netns"]  # where a client-only tool (sim) belongs


@dataclass
class Deployment:
    """Processes serving the keys; ``endpoint``: where this machine's tools connect."""

    endpoint: str
    host_log: Path
    procs: list[subprocess.Popen[Any]] = field(default_factory=list)

    def wait_ready(self) -> None:
        assert wait_until(
            lambda: READY in self.host_log.read_text() or self.procs[-1].poll() is not None, 90
        ), self.host_log.read_text()
        assert self.procs[-1].poll() is None, self.host_log.read_text()


@dataclass
class Topology:
    name: str
    mode: str  # the tools' Zenoh mode: "client" (as the plugin) or "peer"
    deployment: Deployment

    @property
    def endpoint(self) -> str:
        return self.deployment.endpoint

    def zenoh_args(self) -> list[str]:
        return ["--connect", self.endpoint, "--mode", self.mode]


def planner_host(log: Path, *args: str) -> subprocess.Popen[bytes]:
    """``planner-host ARGS`` on this machine, its output in ``log``."""
    with open(log, "wb") as out:
        return subprocess.Popen(
            [sys.executable, "-m", "nav2_pyif.server.cli", *args],
            stdout=out,
            stderr=subprocess.STDOUT,
        )


def deploy(kind: str, directory: Path, stack: contextlib.ExitStack) -> Deployment:
    """``kind``: "listening" (direct, peer), "router" (router, gossip) or "netns"."""
    directory.mkdir()
    config = directory / "planners.yaml"
    config.write_text(yaml.safe_dump(PLANNERS))
    serve = ("--config", str(config), *HOST_ARGS)
    log = directory / "host.log"
    if kind == "listening":
        at = f"tcp/127.0.0.1:{free_port()}"
        deployment = Deployment(at, log, [planner_host(log, "--listen", at, *serve)])
    elif kind == "router":
        at = f"tcp/127.0.0.1:{free_port()}"
        deployment = Deployment(at, log, [start_router("--listen", at)])
        deployment.procs.append(planner_host(log, "--connect", at, *serve))
    else:
        link = stack.enter_context(namespace_link())  # skips, saying why, where not allowed
        inside, local = f"tcp/{SUBNET}.1:{free_port()}", f"tcp/127.0.0.1:{free_port()}"
        deployment = Deployment(local, log, [start_router("--listen", inside, "--listen", local)])
        deployment.procs.append(start_remote_host(link, log, "--connect", inside, *serve))
    stack.callback(stop, deployment.procs[::-1])
    deployment.wait_ready()
    return deployment


@pytest.fixture(scope="module")
def deployments(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Any]:
    """deployment kind -> Deployment, each started on first use, all stopped at the end."""
    made: dict[str, Deployment] = {}
    root = tmp_path_factory.mktemp("topologies")
    with contextlib.ExitStack() as stack:

        def get(kind: str) -> Deployment:
            if kind not in made:
                made[kind] = deploy(kind, root / kind, stack)
            return made[kind]

        yield get


@pytest.fixture(scope="module", params=TOPOLOGIES)
def topology(request: pytest.FixtureRequest, deployments: Any) -> Topology:
    name: str = request.param
    kind = {"direct": "listening", "peer": "listening", "gossip": "router"}.get(name, name)
    mode = "peer" if name in ("peer", "gossip") else "client"
    return Topology(name, mode, deployments(kind))


def test_reference_client(topology: Topology) -> None:
    """The plugin's Python twin: a controller session and a plan, in the topology's mode."""
    session = connect_to([topology.endpoint], topology.mode)
    controller = ControllerClient(session, CONTROLLER_KEY, make_costmap(), timeouts=GENEROUS)
    planner = GlobalPlannerClient(session, PLANNER_KEY, make_costmap(), timeouts=GENEROUS)
    try:
        for client in (controller, planner):
            assert client.wait_for_host(30), topology.deployment.host_log.read_text()
            client.configure()
            client.activate()
        plan = planner.create_plan(pose(0.5, 0.5), pose(1.5, 0.5))
        assert len(plan) > 5 and plan.frame_id == "odom"
        controller.set_plan(plan)
        cmd = controller.compute_velocity_commands(pose(0.5, 0.5), Twist())
        assert 0 < cmd.twist.linear.x <= 1.0, cmd
        for client in (controller, planner):
            client.deactivate()
            client.cleanup()
    finally:
        controller.close()
        planner.close()
        session.close()


def test_reload(topology: Topology) -> None:
    done = tool("reload", "--key", CONTROLLER_KEY, *topology.zenoh_args())
    assert done.returncode == 0, done.stderr
    assert f"{CONTROLLER_KEY}: now serving {CONTROLLER}" in done.stdout


def test_hosts(topology: Topology) -> None:
    """It lists the host with both keys, and says what it went through."""
    done = tool("hosts", "--json", *topology.zenoh_args())
    assert done.returncode == 0, done.stderr
    found = json.loads(done.stdout)
    (host,) = found["hosts"]
    assert {k["key"]: k["planner"] for k in host["keys"]}[CONTROLLER_KEY] == CONTROLLER
    assert {k["key"] for k in host["keys"]} == {CONTROLLER_KEY, PLANNER_KEY}
    routers, peers = len(found["via"]["routers"]), len(found["via"]["peers"])
    expected = {
        "direct": (0, 1),  # the host itself
        "peer": (0, 1),
        "router": (1, 0),
        "netns": (1, 0),
        "gossip": (1, 1),  # the router, and the host reached directly through its gossip
    }
    assert (routers, peers) == expected[topology.name], found["via"]


def test_bench(topology: Topology) -> None:
    """`nav2-pyif-bench host`: the control cycle against the running host, in the tools' mode."""
    done = subprocess.run(
        [sys.executable, "-m", "nav2_pyif_bench.cli", "host", "--key", CONTROLLER_KEY,
         *topology.zenoh_args(), "--calls", "40", "--rate", "0"],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert f"on {CONTROLLER_KEY} (back to back)" in done.stdout, done.stdout
    row = next(line for line in done.stdout.splitlines() if "round trip" in line)
    median, p99, n = row.split()[-3:]
    assert int(n) == 40 and 0 < float(median) <= float(p99), row


@pytest.mark.parametrize("topology", CLIENT_TOPOLOGIES, indirect=True)
def test_sim(topology: Topology, tmp_path: Path) -> None:
    """A short run on the office map: plan and drive 1 m, with the host's planners."""
    done = tool(
        "sim", "--connect", topology.endpoint, "--start", "2", "2.5", "0",
        "--goal", "3", "2.5", "0", "--no-progress", "--out", str(tmp_path),
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    assert "REACHED" in done.stdout and (tmp_path / "office_pure_pursuit.png").is_file()


@pytest.mark.parametrize("topology", ["router"], indirect=True)
def test_no_host_on_the_key_names_the_hosts_seen(topology: Topology, tmp_path: Path) -> None:
    nobody = "nav2_pyif/nobody/FollowPath"
    seen = f"planner hosts visible from here: {CONTROLLER_KEY} (host "
    done = tool("reload", "--key", nobody, "--timeout", "4", *topology.zenoh_args())
    assert done.returncode == 1
    assert f"no planner host on {nobody} yet, waiting up to 4 s; {seen}" in done.stderr
    assert f"no planner host serves {nobody} (no liveliness token" in done.stderr
    assert f"{PLANNER_KEY} (host " in done.stderr and "; reached router " in done.stderr
    done = tool(
        "sim", "--connect", topology.endpoint, "--controller-key", nobody, "--wait", "2",
        "--no-progress", "--out", str(tmp_path),
    )  # fmt: skip
    assert done.returncode == 2
    assert f"no planner host on {nobody} at {topology.endpoint} within 2 s; {seen}" in done.stderr


def test_no_router_names_the_endpoints_tried(tmp_path: Path) -> None:
    nowhere = f"tcp/127.0.0.1:{free_port()}"
    said = f"reached no Zenoh router or peer at all (tried {nowhere})"
    for command in (
        ("reload", "--key", CONTROLLER_KEY, "--connect", nowhere, "--timeout", "1"),
        ("reload", "--key", CONTROLLER_KEY, "--connect", nowhere, "--timeout", "1", "--mode",
         "peer"),  # a peer opens anyway, then finds nothing
        ("sim", "--connect", nowhere, "--wait", "1", "--no-progress", "--out", str(tmp_path)),
        ("hosts", "--connect", nowhere),
    ):  # fmt: skip
        done = tool(*command)
        assert done.returncode in (1, 2) and said in done.stderr, (command, done.stderr)


#: The README's router sequence, and the same with the tool first: each started without
#: waiting for the one before.
SEQUENCES = {
    "readme_order": ("router", "host", "reload"),
    "reload_first": ("reload", "router", "host"),
}


@pytest.mark.parametrize("attempt", range(2))
@pytest.mark.parametrize("order", SEQUENCES)
def test_router_host_and_reload_in_quick_succession(
    tmp_path: Path, order: str, attempt: int
) -> None:
    """README: ``nav2-pyif router``, ``planner-host --key ... --planner ...``, ``nav2-pyif
    reload --key ...``. The reload once failed within a second claiming the full 60 s: sent
    before the router listened or before the host's queryable existed, it found nothing to
    answer. It now waits, up to its timeout, for the router and then for the host's token."""
    at = f"tcp/127.0.0.1:{free_port()}"
    tool_ = [sys.executable, "-m", "nav2_pyif.tools.main"]
    host = ["--connect", at, "--key", CONTROLLER_KEY, "--planner", CONTROLLER, *HOST_ARGS]
    commands = {
        "router": [*tool_, "router", "--listen", at],
        "host": [sys.executable, "-m", "nav2_pyif.server.cli", *host],
        "reload": [*tool_, "reload", "--key", CONTROLLER_KEY, "--connect", at],
    }
    procs: dict[str, subprocess.Popen[str]] = {}
    try:
        with open(tmp_path / "host.log", "w") as log:
            for name in SEQUENCES[order]:
                out = subprocess.PIPE if name == "reload" else log
                procs[name] = subprocess.Popen(commands[name], stdout=out, stderr=out, text=True)
        stdout, stderr = procs["reload"].communicate(timeout=90)
        assert procs["reload"].returncode == 0, stderr + (tmp_path / "host.log").read_text()
        assert f"{CONTROLLER_KEY}: now serving {CONTROLLER}" in stdout
    finally:
        stop([procs[name] for name in ("reload", "host", "router") if name in procs])
