"""tests/test_nav2_launch.py's variants: one per distribution and zenoh-cpp
backend, each skipped where its environment is absent, saying which variable names one; a
setup script that sources another distribution serves only that one, and one named for a
distribution that sources another is refused. Runs that module's launch test in a child
pytest with real setup scripts that stop before anything is built."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]
LAUNCH_TEST = "tests/test_nav2_launch.py::test_nav2_launch_tests_pass_against_a_real_nav2"
DISTROS = ("humble", "jazzy", "lyrical")


def _launch_test(env: dict[str, str], *select: str) -> subprocess.CompletedProcess[str]:
    """The launch test, run with only ``env``'s NAV2_PYIF_NAV2_SETUP* variables."""
    clean = {k: v for k, v in os.environ.items() if not k.startswith("NAV2_PYIF_NAV2_SETUP")}
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q", "-rs", *select],
        capture_output=True,
        text=True,
        timeout=300,
        env={**clean, **env},
        cwd=ROOT,
    )


def _ros_setup(tmp_path: Path, distro: str) -> str:
    """A setup script that sources ROS 2 ``distro`` as far as the test's probe looks first:
    ROS_DISTRO (no Nav2, no colcon)."""
    script = tmp_path / f"setup-{distro}.bash"
    script.write_text(f"export ROS_DISTRO={distro}\n")
    return str(script)


def test_each_distribution_and_backend_is_a_variant_skipped_naming_its_variable() -> None:
    if any(Path(f"/opt/ros/{d}/setup.bash").is_file() for d in DISTROS):
        pytest.skip("a ROS 2 is installed under /opt/ros here: its variant would run")
    run = _launch_test({}, LAUNCH_TEST)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "9 skipped" in run.stdout, run.stdout
    for distro in DISTROS:
        for backend in ("ZENOHC", "ZENOHPICO", "RMW_ZENOH"):
            variable = f"NAV2_PYIF_NAV2_SETUP_{distro.upper()}_{backend}"
            assert variable in run.stdout, f"no skip names {variable}:\n{run.stdout}"


def test_a_shared_setup_script_serves_only_the_distribution_it_sources(tmp_path: Path) -> None:
    jazzy = _ros_setup(tmp_path, "jazzy")
    run = _launch_test({"NAV2_PYIF_NAV2_SETUP_ZENOHPICO": jazzy}, LAUNCH_TEST, "-k", "zenoh-pico")
    assert run.returncode == 0, run.stdout + run.stderr
    for other in ("humble", "lyrical"):
        assert f"on {other} skipped: {jazzy} sources ROS 2 jazzy" in run.stdout, run.stdout
    # The jazzy variant takes it, and goes on to look for Nav2 there.
    assert f"{jazzy} lacks missing: colcon" in run.stdout, run.stdout


def test_a_setup_script_named_for_one_distribution_that_sources_another_fails(
    tmp_path: Path,
) -> None:
    jazzy = _ros_setup(tmp_path, "jazzy")
    run = _launch_test(
        {"NAV2_PYIF_NAV2_SETUP_HUMBLE_ZENOHPICO": jazzy}, LAUNCH_TEST, "-k", "humble-zenoh-pico"
    )
    assert run.returncode == 1, run.stdout + run.stderr
    assert f"NAV2_PYIF_NAV2_SETUP_HUMBLE_ZENOHPICO={jazzy} sources ROS 2 jazzy" in run.stdout
