"""Ready for a release: one version in package.xml, pyproject.toml and the Python
package; the wire protocol's version the same in both codecs, PROTOCOL.md and each release's
changelog entry; a CHANGELOG.rst per ROS package as bloom reads it; one license, stated the
same way in LICENSE, every package.xml and pyproject.toml.

package.xml and CHANGELOG.rst are read with catkin_pkg, the library bloom and
catkin_prepare_release use.
"""

from __future__ import annotations

import configparser
import re
import shutil
from pathlib import Path

import nav2_pyif
import pytest
from catkin_pkg.changelog import get_changelog_from_path
from catkin_pkg.package import parse_package
from catkin_pkg.package_version import get_forthcoming_label, update_changelog_sections
from nav2_pyif_protocol import PROTOCOL_VERSION

from tests.rosdep_fixture import ROOT, package_xmls

# catkin_pkg calls docutils' Node.traverse, which newer docutils deprecates.
pytestmark = [
    pytest.mark.unit,
    pytest.mark.filterwarnings("ignore:nodes.Node.traverse:DeprecationWarning"),
]
PYPROJECT = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
#: The license texts LICENSE may hold, by SPDX identifier: their first lines.
LICENSE_TITLES = {"Apache-2.0": ("Apache License", "Version 2.0, January 2004")}


def _pyproject(field: str) -> str:
    """A string field of pyproject.toml's [project] table (tomllib is Python 3.11+)."""
    project = PYPROJECT.split("[project]", 1)[1].split("\n[", 1)[0]
    match = re.search(rf'^{field} = "([^"]*)"$', project, re.M)
    assert match, f"pyproject.toml [project] has no {field}"
    return match.group(1)


def test_one_version_everywhere() -> None:
    version = _pyproject("version")
    assert nav2_pyif.__version__ == version, "python/nav2_pyif/__init__.py __version__"
    for folder in ("benchmarks", "protocol/codegen"):  # distributions apart from the core
        text = (ROOT / folder / "pyproject.toml").read_text(encoding="utf-8")
        assert f'version = "{version}"' in text, f"{folder}/pyproject.toml's version"
        assert f'"nav2-pyif=={version}"' in text, f"{folder}/pyproject.toml's nav2-pyif"
    for xml in package_xmls():
        assert parse_package(str(xml)).version == version, (
            f"{xml.relative_to(ROOT)} says {parse_package(str(xml)).version}, "
            f"pyproject.toml {version}"
        )


def test_protocol_version_is_one_number() -> None:
    constants = ROOT / "bridge_plugin/include/nav2_pyif_bridge/protocol/constants.hpp"
    cpp = re.search(r"kProtocolVersion = (\d+);", constants.read_text(encoding="utf-8"))
    assert cpp and int(cpp.group(1)) == PROTOCOL_VERSION, "constants.hpp (regenerate it)"
    spec = (ROOT / "protocol/PROTOCOL.md").read_text(encoding="utf-8").splitlines()[0]
    assert spec.endswith(f"version {PROTOCOL_VERSION}"), f"PROTOCOL.md's title: {spec!r}"


@pytest.mark.parametrize("xml", package_xmls(), ids=lambda p: p.parent.name)
def test_changelog_as_bloom_reads_it(xml: Path, tmp_path: Path) -> None:
    package = parse_package(str(xml))
    path = xml.parent / "CHANGELOG.rst"
    assert path.is_file(), f"no {path.relative_to(ROOT)}: bloom releases each package's own"
    changelog = get_changelog_from_path(str(path), package.name)
    assert changelog is not None
    released = [str(v) for v, _, _ in changelog.foreach_version()]
    # Before a release its changes sit under "Forthcoming"; catkin_prepare_release renames
    # that section to "<version> (<date>)". Do that to a copy and read the result.
    label = get_forthcoming_label(changelog.rst)
    if label:
        assert package.version not in released, f"{package.version} was released already"
        copy = tmp_path / "CHANGELOG.rst"
        shutil.copy(path, copy)
        update_changelog_sections(
            {package.name: (str(copy), get_changelog_from_path(str(copy)), label)},
            package.version,
        )
        changelog = get_changelog_from_path(str(copy), package.name)
        assert changelog is not None
    versions = {str(v): content for v, _, content in changelog.foreach_version()}
    assert package.version in versions, (
        f"{path.relative_to(ROOT)} has no section for {package.version} (and no Forthcoming)"
    )
    # Which hosts a release works with: each entry names the protocol version it speaks.
    entry = " ".join(part.as_txt() for part in versions[package.version])
    assert f"protocol version {PROTOCOL_VERSION}" in entry, (
        f"{path.relative_to(ROOT)}'s {package.version} entry does not name the wire "
        f"protocol version it speaks ({PROTOCOL_VERSION})"
    )


def test_one_license_stated_everywhere() -> None:
    spdx = _pyproject("license")
    assert spdx in LICENSE_TITLES, f"pyproject.toml's license {spdx!r} has no known text"
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    assert tuple(lines[:2]) == LICENSE_TITLES[spdx], f"LICENSE is not the {spdx} text"
    for xml in package_xmls():
        licenses = [str(license) for license in parse_package(str(xml)).licenses]
        assert licenses == [spdx], f"{xml.relative_to(ROOT)} states {licenses}, not {spdx}"


def _ament_python_packages() -> list[Path]:
    return [
        xml for xml in package_xmls() if parse_package(str(xml)).get_build_type() == "ament_python"
    ]


def test_colcon_builds_what_pip_installs() -> None:
    """Every folder pip installs Python packages from is a ROS package colcon builds: those of
    the core (pyproject.toml) and the reference planners' own distribution (planners/setup.py,
    the ROS package's); the benchmarks aside, a tool of this repository, not of a robot."""
    match = re.search(r"^where = \[(.*?)\]", PYPROJECT, re.M)
    assert match, "pyproject.toml has no [tool.setuptools.packages.find] where"
    folders = {*re.findall(r'"([^"]+)"', match.group(1)), "planners"}
    assert folders == {str(xml.parent.relative_to(ROOT)) for xml in _ament_python_packages()}


def test_colcon_installs_the_data_files_pip_does() -> None:
    """Each package's data in pyproject.toml (the default Zenoh configs, the runner's maps) is
    in the setup.py colcon builds that package from: without it a workspace's host has none."""
    block = PYPROJECT.split("[tool.setuptools.package-data]", 1)[1].split("\n[", 1)[0]
    rows = re.findall(r'^"([\w.]+)" = \[(.*)\]$', block, re.M)  # "*" (py.typed) aside
    assert rows, block
    for package, listed in rows:
        patterns = re.findall(r'"([^"]+)"', listed)
        top = package.split(".")[0]
        (folder,) = [x.parent for x in _ament_python_packages() if (x.parent / top).is_dir()]
        setup_py = (folder / "setup.py").read_text(encoding="utf-8")
        for pattern in patterns:
            assert pattern in setup_py, f"{folder.name}/setup.py lacks {package}'s {pattern}"


@pytest.mark.parametrize("xml", _ament_python_packages(), ids=lambda p: p.parent.name)
def test_ament_python_packages_install_where_ros_looks(xml: Path) -> None:
    """The ament index marker, and console scripts in lib/<package> (`ros2 run`) run by the
    python3 on PATH (a venv with system site packages, README's Install)."""
    name = parse_package(str(xml)).name
    assert (xml.parent / "resource" / name).is_file(), f"no resource/{name} (ament index)"
    config = configparser.ConfigParser(interpolation=None)
    config.read(xml.parent / "setup.cfg", encoding="utf-8")
    assert config.get("install", "install_scripts") == f"$base/lib/{name}"
    assert config.get("develop", "script_dir") == f"$base/lib/{name}"
    assert config.get("build_scripts", "executable") == "/usr/bin/env python3"
    setup_py = (xml.parent / "setup.py").read_text(encoding="utf-8")
    assert 'ElementTree.parse("package.xml")' in setup_py, "setup.py reads its name and version"
