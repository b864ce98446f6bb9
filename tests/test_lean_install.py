"""A lean core install: `pip install .` pulls what the planner host, the authors' API and the
protocol need (eclipse-zenoh, msgpack, NumPy, PyYAML) and no plotting or progress bars; those
are the ``runner`` extra, which `nav2-pyif sim` names before it starts anything when they are
missing, and without which the host and ``nav2_pyif.testing`` still import."""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

import pytest
from nav2_pyif.tools.main import build_parser
from nav2_pyif_entry import run

from tests.rosdep_fixture import ROOT

pytestmark = pytest.mark.unit

PYPROJECT = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
#: What the core must not pull: the runner's plots and progress bars.
NOT_IN_CORE = {"matplotlib", "tqdm"}


def _requirement_names(block: str) -> set[str]:
    """The distribution names of a TOML list of requirement strings."""
    return {
        re.split(r"[\[<>=!~; ]", req, maxsplit=1)[0].lower()
        for req in re.findall(r'"([^"]+)"', block)
    }


def _core_dependencies() -> set[str]:
    match = re.search(r"^dependencies = \[(.*?)^\]", PYPROJECT, re.M | re.S)
    assert match, "pyproject.toml has no [project] dependencies list"
    return _requirement_names(match.group(1))


def _extra(name: str) -> set[str]:
    match = re.search(rf"^{name} = \[(.*?)\]", PYPROJECT, re.M | re.S)
    assert match, f"pyproject.toml has no extra {name!r}"
    return _requirement_names(match.group(1))


def test_the_core_pulls_no_plotting_or_progress_bars() -> None:
    core = _core_dependencies()
    assert core == {"eclipse-zenoh", "msgpack", "numpy", "pyyaml"}, core
    assert not core & NOT_IN_CORE
    assert _extra("runner") >= NOT_IN_CORE


def test_sim_names_the_runner_extra_when_matplotlib_is_missing(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # as if not installed
    parser, _ = build_parser()
    args = parser.parse_args(["sim", "--out", str(tmp_path)])
    # Before any host starts: the unit tier would fail this test at the first process.
    assert args.func(args) == 1
    err = capsys.readouterr().err
    assert "needs matplotlib" in err and "pip install 'nav2-pyif[runner]'" in err, err
    assert not list(tmp_path.iterdir())


def test_the_host_and_the_authors_testing_helpers_import_without_the_runner_extra(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    for name in NOT_IN_CORE:
        monkeypatch.setitem(sys.modules, name, None)  # importing it raises ImportError
    # Imported afresh, then put back as they were (in sys.modules and as their parents'
    # attributes, which a fresh import rebinds), so later tests see the same modules.
    fresh = [
        name
        for name in sys.modules
        if name.startswith(("nav2_pyif.runner", "nav2_pyif.testing", "nav2_pyif.server"))
    ]
    for name in fresh:
        parent, _, child = name.rpartition(".")
        monkeypatch.setattr(sys.modules[parent], child, sys.modules[name])
    for name in fresh:
        monkeypatch.delitem(sys.modules, name)
    importlib.import_module("nav2_pyif.server.cli")
    testing = importlib.import_module("nav2_pyif.testing")
    assert testing.__name__ == "nav2_pyif.testing"


def test_a_command_without_zenoh_says_how_to_install_it(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """What `ros2 run nav2_pyif planner-host` says in a shell without eclipse-zenoh."""
    monkeypatch.setitem(sys.modules, "zenoh", None)
    assert run("zenoh:open", "planner-host") == 1
    err = capsys.readouterr().err
    assert err.startswith("planner-host: the Python module 'zenoh' cannot be imported by "), err
    assert "pip install eclipse-zenoh" in err and "--system-site-packages" in err, err
