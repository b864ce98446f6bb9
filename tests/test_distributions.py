"""What pip installs, from the wheels pip builds: the core (`pip install .`) holds the planner
host, the authors' API and the protocol and requires eclipse-zenoh, msgpack, NumPy and PyYAML
only; the reference planners (`./planners`), the benchmarks (`./benchmarks`) and the
protocol's code generators (`./protocol/codegen`) are distributions of their own, each
requiring the core of the same release.

Each is built from a copy of the files it is built from (the container image copies the same
ones), so the checkout gets no build folders."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import nav2_pyif
import pytest

from tests.rosdep_fixture import ROOT

pytestmark = pytest.mark.integration

VERSION = nav2_pyif.__version__
#: Each distribution: the files and folders of the checkout it is built from (the first holds
#: its metadata), and the top-level packages its wheel holds.
DISTRIBUTIONS = {
    "nav2_pyif": (
        ["pyproject.toml", "README.md", "protocol", "python"],
        {"nav2_pyif", "nav2_pyif_entry", "nav2_pyif_protocol"},
    ),
    "nav2_pyif_planners": (["planners"], {"nav2_pyif_planners"}),
    "nav2_pyif_bench": (["benchmarks"], {"nav2_pyif_bench"}),
    "nav2_pyif_codegen": (["protocol/codegen"], {"nav2_pyif_codegen"}),
}


def _wheel(name: str, tmp_path: Path) -> zipfile.ZipFile:
    """The wheel pip builds of distribution ``name`` (no network: the venv's setuptools)."""
    sources, _ = DISTRIBUTIONS[name]
    copy = tmp_path / "src"
    for source in sources:
        if (ROOT / source).is_dir():
            ignore = shutil.ignore_patterns("__pycache__", "*.egg-info", "build")
            shutil.copytree(ROOT / source, copy / source, ignore=ignore)
        else:
            copy.mkdir(exist_ok=True)
            shutil.copy(ROOT / source, copy / source)
    project = copy if (copy / "pyproject.toml").is_file() else copy / sources[0]
    pip = [sys.executable, "-m", "pip", "--disable-pip-version-check", "-q"]
    built = subprocess.run(
        [*pip, "wheel", "--no-deps", "--no-build-isolation", "-w", str(tmp_path), str(project)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert built.returncode == 0, built.stdout + built.stderr
    (wheel,) = tmp_path.glob(f"{name}-{VERSION}-*.whl")
    return zipfile.ZipFile(wheel)


def _metadata(wheel: zipfile.ZipFile, name: str) -> str:
    (path,) = [n for n in wheel.namelist() if n.endswith(f".dist-info/{name}")]
    return wheel.read(path).decode()


def _requires(wheel: zipfile.ZipFile) -> set[str]:
    """The requirements the wheel pulls whatever the extras: name==version, or the name."""
    found = set()
    for line in _metadata(wheel, "METADATA").splitlines():
        if line.startswith("Requires-Dist: ") and "extra ==" not in line:
            req = line.removeprefix("Requires-Dist: ")
            name = re.split(r"[\[<>=!~; ]", req, maxsplit=1)[0].lower()
            found.add(req if "==" in req else name)
    return found


@pytest.mark.parametrize("name", DISTRIBUTIONS)
def test_each_wheel_holds_its_own_packages_only(name: str, tmp_path: Path) -> None:
    wheel = _wheel(name, tmp_path)
    # (the planners' .data: the ament index marker and package.xml, as colcon installs them)
    tops = {n.split("/")[0] for n in wheel.namelist() if not re.search(r"\.(dist-info|data)/", n)}
    assert tops == DISTRIBUTIONS[name][1]


def test_the_core_pulls_no_plotting_planners_or_benchmarks(tmp_path: Path) -> None:
    wheel = _wheel("nav2_pyif", tmp_path)
    assert _requires(wheel) == {"eclipse-zenoh", "msgpack", "numpy", "pyyaml"}
    scripts = _metadata(wheel, "entry_points.txt")
    assert "planner-host =" in scripts and "nav2-pyif-bench" not in scripts, scripts
    assert "nav2-pyif-vectors" not in scripts, scripts  # the code generators' (development)


def test_the_planners_require_the_core_of_their_release(tmp_path: Path) -> None:
    wheel = _wheel("nav2_pyif_planners", tmp_path)
    assert _requires(wheel) == {"setuptools", f"nav2-pyif=={VERSION}", "numpy"}
    # Nav2 Jazzy's MPPI block, which Nav2MPPI reads
    assert "nav2_pyif_planners/mppi_nav2/nav2_jazzy.yaml" in wheel.namelist()


def test_the_benchmarks_bring_their_command_and_what_it_plots_with(tmp_path: Path) -> None:
    wheel = _wheel("nav2_pyif_bench", tmp_path)
    assert _requires(wheel) == {
        f"nav2-pyif=={VERSION}",
        f"nav2-pyif-planners=={VERSION}",
        "matplotlib",
        "cryptography",
    }
    assert "nav2-pyif-bench = nav2_pyif_entry:nav2_pyif_bench" in _metadata(
        wheel, "entry_points.txt"
    )


def test_the_code_generators_bring_the_vectors_command(tmp_path: Path) -> None:
    wheel = _wheel("nav2_pyif_codegen", tmp_path)
    assert _requires(wheel) == {f"nav2-pyif=={VERSION}"}
    scripts = _metadata(wheel, "entry_points.txt")
    assert "nav2-pyif-vectors = nav2_pyif_codegen.vectors:main" in scripts, scripts
