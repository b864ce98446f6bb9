"""The deployment guide's secure fleet (section 6) in the real Nav2: certificates made by the
guide's openssl commands, the fleet router (`router-secure.json5`: TLS only, client
certificates, access control by certificate name), the planner host (`host-secure.json5`),
and robot1's plugins: on zenoh-c with `plugin-secure.json5` through `zenoh_config`, on
zenoh-pico through the robot's own router (`robot-router-secure.json5`: loopback TCP for the
plugins, mutual TLS to the fleet). Every file as the guide writes it, but for the certificate
directory and the addresses. robot1 plans and drives to its goal through all of that.

Needs what test_nav2_pyif.py needs, `openssl`, and `nav2-pyif` (through $NAV2_PYIF_RUN or
on PATH) for the routers.
"""

from __future__ import annotations

import math
import os
import re
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_testing
import pytest

from tests.docs_blocks import guide_certificates

ROOT = nav2_testing.HERE.parents[2]
ZENOH_FILES = ROOT / "docs" / "zenoh"
ROBOT = "nav2_pyif/robot1"  # the keys robot1's certificate may call (router-secure.json5)
GOAL = (2.0, 0.5)
ROUTER_LOG = "zenoh=warn,zenoh::net::routing::interceptor::access_control=debug"


def guide_file(name: str, tls: Path, into: Path, **endpoints: str) -> Path:
    """docs/zenoh/NAME as written, its /etc/nav2_pyif/tls/ the test's, and each endpoint
    ``old=new`` replaced (keyword names are unused labels)."""
    text = (ZENOH_FILES / name).read_text().replace("/etc/nav2_pyif/tls/", f"{tls}/")
    for old_new in endpoints.values():
        old, new = old_new.split("=", 1)
        assert old in text, f"{name} no longer names {old}"
        text = text.replace(old, new)
    path = into / name
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    router = nav2_testing.project_command("nav2-pyif")
    if router is None or shutil.which("openssl") is None:
        pytest.skip("the secure-fleet test needs nav2-pyif ($NAV2_PYIF_RUN) and openssl")
    logs = tmp_path_factory.mktemp("nav2_secure_fleet")
    tls = guide_certificates(logs, "127.0.0.1")
    fleet = f"tls/127.0.0.1:{nav2_testing.free_port()}"
    pico = os.environ.get("NAV2_PYIF_ZENOH_BACKEND") == "zenoh-pico"
    robot_router = f"tcp/127.0.0.1:{nav2_testing.free_port()}"
    plugin_file = guide_file(
        "plugin-secure.json5", tls, logs, router="tls/192.168.1.20:7447=" + fleet
    )

    def robot1_params(text: str) -> str:
        """robot1's keys; its plugins' Zenoh: the guide's file, or the robot's router."""
        text = text.replace(nav2_testing.PREFIX, ROBOT)
        if pico:
            return re.sub(r'zenoh_connect: \[".*"\]', f'zenoh_connect: ["{robot_router}"]', text)
        return re.sub(r'zenoh_config: ".*"', f'zenoh_config: "{plugin_file}"', text)

    def secure_fleet(procs: nav2_testing.Processes, endpoint: str) -> tuple[list[str], list[str]]:
        """The fleet router (and on pico the robot's router); the host's secure file."""
        routed = guide_file("router-secure.json5", tls, logs, listen="tls/0.0.0.0:7447=" + fleet)
        logged = ["env", f"RUST_LOG={ROUTER_LOG}", *router, "router"]  # denials named
        procs.start("fleet_router", [*logged, "--zenoh-config", str(routed)])
        if pico:
            robot = guide_file(
                "robot-router-secure.json5",
                tls,
                logs,
                listen="tcp/127.0.0.1:7447=" + robot_router,
                connect="tls/192.168.1.20:7447=" + fleet,
            )
            procs.start("robot_router", [*router, "router", "--zenoh-config", str(robot)])
        host = guide_file("host-secure.json5", tls, logs, connect="tls/192.168.1.20:7447=" + fleet)
        return [], ["--zenoh-config", str(host)]

    planners = (
        *("--serve", f"{ROBOT}/FollowPath=nav2_pyif_planners.pure_pursuit:"
          "RegulatedPurePursuit"),
        *("--serve", f"{ROBOT}/GridBased=nav2_pyif_planners.astar:AStar"),
    )  # fmt: skip
    yield from nav2_testing.bring_up(
        logs, planners=planners, edit_params=robot1_params, topology=secure_fleet
    )


def test_robot1_plans_and_drives_through_the_secure_fleet(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    names = ("planner_server", "controller_server", "planner_host", "fleet_router")
    states = client.wait_active(nav2_testing.SERVERS, 90.0)
    logs = "\n".join(procs.log(n) for n in names)
    assert all(s == "active" for s in states.values()), f"{states}\n{logs}"
    planned = client.plan(*GOAL)
    logs = "\n".join(procs.log(n) for n in names)
    assert planned is not None and planned.status == nav2_testing.SUCCEEDED, logs
    handle = client.follow(planned.result.path)
    result = client.wait(handle.get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in names)
    assert result is not None and result.status == nav2_testing.SUCCEEDED, f"{result}\n{logs}"
    x, y = client.pose
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}, goal {GOAL}"
    assert " is alive on " in procs.log("controller_server", 200)
