"""``nav2-pyif hosts`` over real processes: two planner hosts on different keys behind a
``nav2-pyif router``, the tool a client of that router (as ros2cli's tools are)."""

from __future__ import annotations

import json
import subprocess
from typing import Any

import pytest
from nav2_pyif.client import ControllerClient

from tests.conftest import free_port, make_costmap, nav2_pyif_tool, wait_until
from tests.test_env_and_router import start_router
from tests.test_host_e2e import GENEROUS

pytestmark = pytest.mark.integration

CONTROLLER_KEY = "nav2_pyif/robot1/FollowPath"
PLANNER_KEY = "nav2_pyif/robot2/GridBased"


def hosts_tool(*args: str) -> subprocess.CompletedProcess[str]:
    return nav2_pyif_tool("hosts", *args, timeout=30)


def listed(router_at: str) -> dict[str, Any]:
    """host id -> the tool's JSON entry."""
    done = hosts_tool("--connect", router_at, "--json")
    assert done.returncode in (0, 1), done.stderr
    return {h["host_id"]: h for h in json.loads(done.stdout)["hosts"]}


def test_hosts_lists_both_hosts_their_sessions_and_not_a_killed_one(
    start_host: Any, zsession_factory: Any
) -> None:
    router_at = f"tcp/127.0.0.1:{free_port()}"
    router = start_router("--listen", router_at)
    try:
        controller = start_host(
            "--key", CONTROLLER_KEY, "--planner", "echo_planners:EchoController",
            "--connect", router_at,
        )  # fmt: skip
        planner = start_host(
            "--key", PLANNER_KEY, "--planner", "echo_planners:LinePlanner",
            "--connect", router_at, "--isolation", "none",
        )  # fmt: skip
        for host in (controller, planner):
            assert wait_until(lambda h=host: " ready (" in h.log(), 30), host.log()

        found = listed(router_at)
        assert len(found) == 2, found
        by_key = {k["key"]: (h, k) for h in found.values() for k in h["keys"]}
        host, entry = by_key[CONTROLLER_KEY]
        assert entry["planner"] == "echo_planners:EchoController"
        assert (entry["plugin_type"], entry["isolation"], entry["sessions"]) == (
            "controller", "process", 0,
        )  # fmt: skip
        assert host["pid"] == controller.proc.pid and host["uptime"] >= 0
        host, entry = by_key[PLANNER_KEY]
        assert entry["planner"] == "echo_planners:LinePlanner"
        assert (entry["plugin_type"], entry["isolation"]) == ("global_planner", "none")
        assert host["pid"] == planner.proc.pid

        # A session opened by the reference client (the plugin's side) is counted.
        session = zsession_factory(router_at, mode="client")
        client = ControllerClient(session, CONTROLLER_KEY, make_costmap(), timeouts=GENEROUS)
        assert client.wait_for_host(20)
        client.configure()
        client.activate()
        table = hosts_tool("--connect", router_at)
        assert table.returncode == 0, table.stderr
        router_zid = json.loads(hosts_tool("--connect", router_at, "--json").stdout)["via"]
        assert table.stdout.startswith(f"via router {router_zid['routers'][0]}"), table.stdout
        rows = {line.split()[0]: line.split() for line in table.stdout.splitlines() if line}
        # one session; two queries answered (configure, activate)
        assert rows[CONTROLLER_KEY][1:] == ["echo_planners:EchoController", "controller",
                                            "process", "1", "2"], table.stdout  # fmt: skip
        assert rows[PLANNER_KEY][1:] == ["echo_planners:LinePlanner", "global_planner",
                                         "none", "0", "0"], table.stdout  # fmt: skip
        assert table.stdout.count("\nhost ") == 2, table.stdout

        planner.kill()  # SIGKILL: its token goes when the router sees the link drop
        assert wait_until(lambda: len(listed(router_at)) == 1, 20)
        (remaining,) = listed(router_at).values()
        assert [k["key"] for k in remaining["keys"]] == [CONTROLLER_KEY]

        controller.kill()
        assert wait_until(lambda: not listed(router_at), 20)
        done = hosts_tool("--connect", router_at)
        assert done.returncode == 1
        assert "but no planner host is visible there" in done.stderr, done.stderr
    finally:
        router.terminate()
        router.wait(10)


def test_no_router_is_exit_1_naming_the_endpoints_tried() -> None:
    nowhere = f"tcp/127.0.0.1:{free_port()}"
    done = hosts_tool("--connect", nowhere)  # a client: fails to open
    assert done.returncode == 1 and done.stdout == ""
    assert f"reached no Zenoh router or peer at all (tried {nowhere})" in done.stderr
    assert "nav2-pyif router" in done.stderr
    done = hosts_tool("--connect", nowhere, "--mode", "peer", "--wait", "0.2")  # opens anyway
    assert done.returncode == 1
    assert f"reached no Zenoh router or peer at all (tried {nowhere})" in done.stderr
