"""Every Zenoh config file the project ships carries the defaults the built-in config applies.

A config file replaces the built-in configuration as a whole (nav2_pyif.common.zenoh_config:
with --zenoh-config nothing built-in is added), so a file that leaves out the 1 s lease makes
a host using it look alive for Zenoh's 10 s after its machine vanished. Each file is loaded
through zenoh's own parser and its effective values (what zenoh fills in for what the file
leaves out included) are compared with the built-in configuration of the same mode.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
import zenoh
from nav2_pyif.common.zenoh_config import ZenohOptions, build_config

from tests.conftest import ROOT

pytestmark = pytest.mark.unit

#: What every session the project configures gets: a 1 s lease with 4 keep-alives per lease,
#: no multicast scouting.
EVERYWHERE = [
    "transport/link/tx/lease",
    "transport/link/tx/keep_alive",
    "scouting/multicast/enabled",
]
#: Only where the session connects somewhere: a router (or link) that comes back is
#: re-joined within 0.5 s.
WHEN_CONNECTING = ["connect/retry"]
#: Only for the Python programs (planner-host, nav2-pyif router and tools): the C++ plugin's
#: built-in config (bridge_plugin/src/nav2/zenoh_transport.cpp) leaves shared memory as
#: zenoh-c has it.
PYTHON_ONLY = ["transport/shared_memory/enabled"]


def shipped() -> list[Path]:
    """Every JSON5 file under version control: docs/zenoh/*.json5 and any added elsewhere."""
    listed = subprocess.run(
        ["git", "ls-files", "*.json5"], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout.split()
    return [ROOT / name for name in listed] or sorted((ROOT / "docs" / "zenoh").glob("*.json5"))


def effective(config: zenoh.Config, key: str) -> object:
    return json.loads(config.get_json(key) or "null")


def expected_keys(config: zenoh.Config, path: Path) -> list[str]:
    keys = list(EVERYWHERE)
    if effective(config, "connect/endpoints"):
        keys += WHEN_CONNECTING
    if not path.name.startswith("plugin-"):  # the Nav2 plugin's own files
        keys += PYTHON_ONLY
    return keys


def test_every_docs_zenoh_file_is_checked() -> None:
    checked = {path.name for path in shipped()}
    assert {path.name for path in (ROOT / "docs" / "zenoh").glob("*.json5")} <= checked
    assert "host-listen.json5" in checked


@pytest.mark.parametrize("path", shipped(), ids=lambda p: str(p.relative_to(ROOT)))
def test_shipped_config_carries_the_built_in_defaults(path: Path) -> None:
    config = zenoh.Config.from_file(str(path))
    mode = effective(config, "mode")
    assert mode in ("peer", "client", "router"), f"{path.name}: no mode"
    built_in = build_config(ZenohOptions(mode=str(mode), use_environment=False))
    wrong = {
        key: (effective(config, key), effective(built_in, key))
        for key in expected_keys(config, path)
        if effective(config, key) != effective(built_in, key)
    }
    assert not wrong, f"{path.name}: key: (the file's effective value, built-in): {wrong}"


def test_the_built_in_lease_is_the_documented_one() -> None:
    """The numbers README and docs/DEPLOYMENT.md state: a 1 s lease, keep-alives every
    250 ms, reconnect within 0.5 s."""
    built_in = build_config(ZenohOptions(use_environment=False))
    assert effective(built_in, "transport/link/tx/lease") == 1000
    assert effective(built_in, "transport/link/tx/keep_alive") == 4
    retry = effective(built_in, "connect/retry")
    assert isinstance(retry, dict) and retry["period_max_ms"] == 500
    guide = (ROOT / "docs" / "DEPLOYMENT.md").read_text()
    assert "1 s lease with keep-alives every 250 ms" in guide
    assert "re-joined within 0.5 s" in guide
