"""testenv/build.sh's rmw-zenoh step: only Jazzy's and Lyrical's recipes have rmw_zenoh, so a
default run of Humble (every step, in order) goes past it to the setup scripts, while Jazzy's and
Lyrical's name the sources they lack."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from tests.testenv_build import run_build

pytestmark = [
    pytest.mark.integration,  # runs build.sh
    pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash"),
]


def _rmw_zenoh_step(tmp_path: Path, distro: str) -> subprocess.CompletedProcess[str]:
    """build.sh DISTRO rmw-zenoh on an empty source tree, into tmp_path/prefix."""
    return run_build(tmp_path, distro, "rmw-zenoh", timeout=60)


def test_humble_has_no_rmw_zenoh_recipe(tmp_path: Path) -> None:
    result = _rmw_zenoh_step(tmp_path, "humble")
    assert result.returncode == 0, result.stderr
    assert "nothing to do for humble" in result.stderr
    # The run goes on as after any step: the setup scripts are written.
    assert (tmp_path / "prefix" / "setup-zenoh-pico.bash").is_file()


@pytest.mark.parametrize("distro", ["jazzy", "lyrical"])
def test_rmw_zenoh_names_its_missing_sources(tmp_path: Path, distro: str) -> None:
    result = _rmw_zenoh_step(tmp_path, distro)
    assert result.returncode == 1
    assert "no rmw_zenoh sources (ros2/rmw_zenoh in" in result.stderr
