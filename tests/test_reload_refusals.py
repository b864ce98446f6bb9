"""``nav2-pyif reload`` against a real planner host: a swap that changes a key's plugin type
is refused unless asked for, every refusal is in the host's log, and each swap is said there
once."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from tests.conftest import nav2_pyif_tool, wait_until

pytestmark = pytest.mark.integration

KEY = "nav2_pyif/swap/FollowPath"
CONTROLLER = "echo_planners:EchoController"
PLANNER = "echo_planners:LinePlanner"

VALID = """
from nav2_pyif import Controller


class Swapped(Controller):
    def compute_velocity_commands(self, pose, velocity, goal_checker):
        raise NotImplementedError
"""


def reload(host: Any, *args: str) -> Any:
    return nav2_pyif_tool("reload", "--key", KEY, "--connect", host.endpoint, *args)


def test_a_swap_to_another_plugin_type_needs_asking(start_host: Any) -> None:
    host = start_host(
        "--key", KEY, "--planner", CONTROLLER, "--allow-remote-reload", "--reload-allow", "*"
    )
    refused = reload(host, "--planner", PLANNER)
    assert refused.returncode == 1, refused.stderr
    assert f"{PLANNER} is a global_planner; this key serves a controller" in refused.stderr
    assert "--allow-type-change" in refused.stderr
    warning = f"[WARNING] [nav2_pyif.server.host] {KEY}: refused a remote reload ({PLANNER}): "
    assert wait_until(lambda: warning in host.log(), 5), host.log()
    info = nav2_pyif_tool("hosts", "--connect", host.endpoint, "--json")
    assert '"plugin_type": "controller"' in info.stdout, info.stdout  # still the controller

    swapped = reload(host, "--planner", PLANNER, "--allow-type-change")
    assert swapped.returncode == 0, swapped.stderr
    assert f"{KEY}: now serving {PLANNER}" in swapped.stdout
    info = nav2_pyif_tool("hosts", "--connect", host.endpoint, "--json")
    assert '"plugin_type": "global_planner"' in info.stdout, info.stdout
    assert host.log().count(f"now serving {PLANNER}") == 1, host.log()  # said once


def test_a_reload_refused_for_a_syntax_error_is_logged_on_the_host(
    start_host: Any, tmp_path: Path
) -> None:
    (tmp_path / "swap_me.py").write_text(VALID)
    host = start_host(
        "--key", KEY, "--planner", "swap_me:Swapped", "--path", str(tmp_path),
        "--allow-remote-reload",
    )  # fmt: skip
    assert wait_until(lambda: "ready" in host.log(), 30), host.log()
    (tmp_path / "swap_me.py").write_text(VALID.replace("def compute", "def compute(("))
    refused = reload(host)
    assert refused.returncode == 1, refused.stderr
    assert "SyntaxError" in refused.stderr, refused.stderr
    said = f"{KEY}: refused a remote reload (a fresh import of swap_me:Swapped): "
    assert wait_until(lambda: said in host.log(), 5), host.log()
    assert "SyntaxError" in host.log().split(said, 1)[1], host.log()
