"""Every Zenoh config file the project ships carries the settings of the default ones.

The defaults are files too (nav2_pyif_protocol/zenoh/<mode>.json5, loaded by the planner host
and the tools, and copied by `generate` into the Nav2 plugin's package). A config file named
instead replaces the default as a whole (with --zenoh-config nothing of it is added), so a file
that leaves out the 1 s lease makes a host using it look alive for Zenoh's 10 s after its
machine vanished. Each file is loaded through zenoh's own parser and its effective values (what
zenoh fills in for what the file leaves out included) are compared with the default of the same
mode.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
import zenoh
from nav2_pyif.common.zenoh_config import ZenohOptions, build_config
from nav2_pyif_protocol import zenoh_defaults

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
#: Not required of the guide's files for the Nav2 plugin (plugin-*.json5): a client sending
#: small requests need not turn off what it never uses.
PYTHON_ONLY = ["transport/shared_memory/enabled"]


def shipped() -> list[Path]:
    """Every JSON5 file under version control: docs/zenoh/*.json5, the defaults, and any
    added elsewhere."""
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
    assert {"host-listen.json5", "peer.json5", "client.json5", "default_session.json5"} <= checked


def test_the_plugin_loads_the_client_default() -> None:
    """The Nav2 plugin's installed default (zenoh-c) is the tools' client default, copied by
    `generate` (its --check keeps them equal); it is installed with the package."""
    plugin = ROOT / zenoh_defaults.BRIDGE_COPY
    assert plugin.read_text().endswith(zenoh_defaults.path("client").read_text())
    cmake = (ROOT / "bridge_plugin" / "CMakeLists.txt").read_text()
    assert "install(DIRECTORY config " in cmake
    assert "/share/${PROJECT_NAME}/config/default_session.json5" in cmake
    source = (ROOT / "bridge_plugin" / "src" / "nav2" / "zenoh_transport.cpp").read_text()
    assert "file.empty() ? NAV2_PYIF_DEFAULT_ZENOH_CONFIG : file" in source


@pytest.mark.parametrize("path", shipped(), ids=lambda p: str(p.relative_to(ROOT)))
def test_shipped_config_carries_the_built_in_defaults(path: Path) -> None:
    config = zenoh.Config.from_file(str(path))
    mode = effective(config, "mode")
    assert mode in ("peer", "client", "router"), f"{path.name}: no mode"
    default = build_config(ZenohOptions(mode=str(mode), use_environment=False))
    wrong = {
        key: (effective(config, key), effective(default, key))
        for key in expected_keys(config, path)
        if effective(config, key) != effective(default, key)
    }
    assert not wrong, f"{path.name}: key: (the file's effective value, the default's): {wrong}"


def test_the_built_in_lease_is_the_documented_one() -> None:
    """The numbers README and python/doc/howto/deployment.md state: a 1 s lease, keep-alives every
    250 ms, reconnect within 0.5 s."""
    built_in = build_config(ZenohOptions(use_environment=False))
    assert effective(built_in, "transport/link/tx/lease") == 1000
    assert effective(built_in, "transport/link/tx/keep_alive") == 4
    retry = effective(built_in, "connect/retry")
    assert isinstance(retry, dict) and retry["period_max_ms"] == 500
    guide = (ROOT / "python" / "doc" / "howto" / "deployment.md").read_text()
    assert "1 s lease with keep-alives every 250 ms" in guide
    assert "re-joined within 0.5 s" in guide
