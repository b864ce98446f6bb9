"""The params file the plugin package ships (bridge_plugin/params): `ros2 launch nav2_pyif_bridge
nav2_pyif.launch.py` passes it alone when the user names none, so every plugin it lists must be
loadable from it alone. Nav2 dies at configure on a listed name without a `plugin` parameter
("Can not get 'plugin' param value for inflation_layer": a crash, exit -11, found by trying the
launch as a new user)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

pytestmark = pytest.mark.unit

PARAMS = sorted((Path(__file__).resolve().parents[1] / "bridge_plugin" / "params").glob("*.yaml"))


def plugin_lists(section: Any, where: str = "") -> Iterator[tuple[str, dict[str, Any], list[str]]]:
    """Every `*_plugins` / `plugins` list in the file, with the section that holds it."""
    if not isinstance(section, dict):
        return
    for key, value in section.items():
        if key.endswith("plugins") and isinstance(value, list):
            yield f"{where}{key}", section, value
        else:
            yield from plugin_lists(value, f"{where}{key}.")


def test_there_is_a_shipped_params_file() -> None:
    assert [p.name for p in PARAMS] == ["nav2_pyif_params.yaml"]


@pytest.mark.parametrize("path", PARAMS, ids=lambda p: p.name)
def test_every_listed_plugin_is_defined_in_the_file(path: Path) -> None:
    lists = list(plugin_lists(yaml.safe_load(path.read_text())))
    assert lists, f"{path.name} lists no plugins"
    for where, section, names in lists:
        for name in names:
            entry = section.get(name)
            assert isinstance(entry, dict) and isinstance(entry.get("plugin"), str), (
                f"{path.name}: {where} lists {name!r}, which has no `plugin:` in this file"
            )


def test_the_check_finds_a_listed_layer_without_its_plugin() -> None:
    broken = {"local_costmap": {"local_costmap": {"ros__parameters": {
        "plugins": ["keepout", "inflation_layer"],
        "keepout": {"plugin": "nav2_pyif_bridge::PyCostmapLayer"},
    }}}}  # fmt: skip
    missing = [
        name
        for _, section, names in plugin_lists(broken)
        for name in names
        if not isinstance(section.get(name), dict)
    ]
    assert missing == ["inflation_layer"]
