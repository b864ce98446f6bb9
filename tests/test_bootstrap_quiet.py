"""scripts/bootstrap.sh installs editable without setuptools' BuildBackendWarning blocks
("Editable installation. Please be careful with folders ..."): the filter it sets, tried on a
real editable install of a project laid out as this one (packages under two folders, so setuptools
takes its meta path finder, the strategy that warns)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = """\
[build-system]
requires = ["setuptools>=77"]
build-backend = "setuptools.build_meta"

[project]
name = "quiet-probe"
version = "0.1"

[tool.setuptools.packages.find]
where = ["python", "protocol"]
"""


def bootstrap_filter() -> str:
    """The PYTHONWARNINGS bootstrap.sh gives pip, as it computes it."""
    line = next(
        line
        for line in (ROOT / "scripts/bootstrap.sh").read_text().splitlines()
        if line.startswith("QUIET=")
    )
    done = subprocess.run(
        ["bash", "-c", f'{line}; printf %s "$QUIET"'],
        capture_output=True,
        text=True,
        env={k: v for k, v in os.environ.items() if k != "PYTHONWARNINGS"},
        check=True,
    )
    return done.stdout


def editable_install(tmp_path: Path, warnings: str | None) -> str:
    project = tmp_path / "project"
    for folder, package in (("python", "quiet_probe"), ("protocol", "quiet_probe_protocol")):
        (project / folder / package).mkdir(parents=True, exist_ok=True)
        (project / folder / package / "__init__.py").write_text("")
    (project / "pyproject.toml").write_text(PYPROJECT)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONWARNINGS"}
    if warnings is not None:
        env["PYTHONWARNINGS"] = warnings
    done = subprocess.run(
        [
            *(sys.executable, "-m", "pip", "--disable-pip-version-check", "-q", "install"),
            *("--no-deps", "--no-build-isolation", "--no-index"),
            *("--prefix", str(tmp_path / "prefix"), "-e", str(project)),
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=180,
    )
    assert done.returncode == 0, done.stderr
    return done.stderr


def test_bootstraps_editable_install_shows_no_build_backend_warning(tmp_path: Path) -> None:
    assert "BuildBackendWarning: Editable installation." in editable_install(tmp_path, None)
    assert "BuildBackendWarning" not in editable_install(tmp_path, bootstrap_filter())
