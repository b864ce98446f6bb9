"""Installed the way a Nav2 user installs: a fresh colcon workspace with a `git clone` of this
checkout in src/, `colcon build` (the C++ plugins and the Python side: nav2_pyif,
nav2_pyif_planners, nav2_pyif_protocol), `ros2 run nav2_pyif planner-host --help`,
`colcon test` with `colcon test-result --verbose`, and `ros2 launch nav2_pyif_bridge
nav2_pyif.launch.py` reaching a goal against the simulated robot with the planner host from
the workspace's install space (bridge_plugin/test/nav2/test_launch_file.py, given no host).

One variant per distribution. Each needs a ROS 2 with Nav2, colcon and zenoh-cpp over
zenoh-pico, named as for tests/test_nav2_launch.py (NAV2_PYIF_NAV2_SETUP_<DISTRO>_ZENOHPICO, or
the shared NAV2_PYIF_NAV2_SETUP_ZENOHPICO for the distribution it sources), and eclipse-zenoh
importable there (it has no rosdep key: README, Install). Skipped, saying what is missing,
otherwise. It tests the committed HEAD (what `git clone` gives), and prints each step's time
(README's Install section records them).
"""

from __future__ import annotations

import shlex
import shutil
import subprocess
import time
from pathlib import Path

import pytest

from tests.test_nav2_launch import DISTROS, ROOT, _bash, _own_variable, _setup_script, _tail

pytestmark = pytest.mark.nav2

BACKEND = "zenoh-pico"
PYTHON_PACKAGES = ("nav2_pyif", "nav2_pyif_planners", "nav2_pyif_protocol")
LAUNCH_TEST = "src/nav2_pyif/bridge_plugin/test/nav2/test_launch_file.py"


def _setup_or_skip(distro: str, trial: str, needs: str) -> str:
    """``distro``'s setup script, or the trial skipped saying what it needs (``needs``, with
    ``{distro}`` filled in) and where to name it."""
    setup = _setup_script(distro, BACKEND)
    if not setup:
        pytest.skip(
            f"the {distro} {trial} needs {needs.format(distro=distro)}: set "
            f"{_own_variable(distro, BACKEND)} (testenv/build.sh {distro} writes one)"
        )
    return setup


def _step(workspace: Path, name: str, source: str, command: str, timeout: float) -> str:
    """One shell step in ``workspace``, timed; its output, or the test fails with its tail."""
    began = time.monotonic()
    done = _bash(f"cd {shlex.quote(str(workspace))}; {source}; {command}", timeout=timeout)
    print(f"{name}: {time.monotonic() - began:.0f} s ({command})")
    assert done.returncode == 0, f"{command} failed:\n" + _tail(done, 60)
    return done.stdout + done.stderr


@pytest.mark.timeout(3600)
@pytest.mark.parametrize("distro", DISTROS)
def test_a_fresh_workspace_builds_tests_and_launches_from_its_install_space(distro: str) -> None:
    setup = _setup_or_skip(distro, "workspace trial", "a ROS 2 {distro} with Nav2 and zenoh-pico")
    source = f"set -e; source {shlex.quote(setup)} >/dev/null"
    probe = _bash(
        f'{source}; [ "$ROS_DISTRO" = {distro} ] || echo missing: ROS 2 {distro}, got $ROS_DISTRO; '
        "command -v colcon >/dev/null || echo missing: colcon; "
        "python3 -c 'import zenoh' 2>/dev/null || echo missing: eclipse-zenoh",
        timeout=60,
    )
    missing = [line for line in probe.stdout.splitlines() if line.startswith("missing:")]
    if probe.returncode != 0 or missing:
        pytest.skip(f"the workspace trial: {setup} lacks {missing or _tail(probe, 5)}")

    workspace = ROOT / "build" / f"ros_workspace_{distro}"
    shutil.rmtree(workspace, ignore_errors=True)
    (workspace / "src").mkdir(parents=True)
    subprocess.run(
        ["git", "clone", "-q", str(ROOT), str(workspace / "src" / "nav2_pyif")], check=True
    )
    listed = _step(workspace, "colcon list", source, "colcon list --names-only", 120).split()
    assert {"nav2_pyif_bridge", *PYTHON_PACKAGES} <= set(listed), listed

    _step(workspace, "colcon build", source, "colcon build", 3000)
    installed = f"{source}; source install/setup.bash"
    usage = _step(workspace, "ros2 run", installed, "ros2 run nav2_pyif planner-host --help", 120)
    assert "usage: planner-host" in usage, usage

    _step(workspace, "colcon test", installed, "colcon test", 1200)
    results = _step(workspace, "colcon test-result", installed, "colcon test-result --verbose", 120)
    assert "0 errors, 0 failures" in results, results

    # The launch file with no planner_host argument: the host from the install space.
    launched = _step(
        workspace,
        "ros2 launch",
        f"{installed}; unset NAV2_PYIF_PLANNER_HOST NAV2_PYIF_RUN",
        f"python3 -m pytest -p no:cacheprovider -q -rs {LAUNCH_TEST}",
        900,
    )
    assert " passed" in launched and "skipped" not in launched, launched


@pytest.mark.timeout(1800)
@pytest.mark.parametrize("distro", DISTROS)
def test_the_host_alone_installs_with_pip_into_a_venv_beside_ros(
    distro: str, tmp_path: Path
) -> None:
    """README's other way (Install, "Only the host, with pip"): beside a sourced ROS 2, a venv
    made with --system-site-packages, `pip install` of a clone; its planner-host runs from
    the venv and sees ROS 2's own message packages (rclpy's, not wheels)."""
    setup = _setup_or_skip(distro, "pip-beside-ROS trial", "a ROS 2 {distro}")
    source = f"set -e; source {shlex.quote(setup)} >/dev/null"
    probe = _bash(
        f'{source}; echo "distro: $ROS_DISTRO"; python3 -c "import sys, rclpy; '
        "inside = sys.prefix != sys.base_prefix and rclpy.__file__.startswith(sys.prefix); "
        "print('in a venv' if inside else 'on PYTHONPATH')\"",
        timeout=60,
    )
    if probe.returncode != 0 or f"distro: {distro}" not in probe.stdout:
        pytest.skip(f"the pip-beside-ROS trial: {setup} does not source ROS 2 {distro}")
    if "in a venv" in probe.stdout:
        # A ROS 2 from PyPI wheels (testenv's Jazzy) is itself a venv: a venv made beside it
        # does not see it. README's venv way is for a ROS 2 whose Python packages are on
        # PYTHONPATH (apt's /opt/ros, or one built from source).
        pytest.skip(f"the pip-beside-ROS trial: {setup}'s ROS 2 Python packages are in a venv")
    clone, venv = tmp_path / "nav2_pyif", tmp_path / "venv"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
    _step(tmp_path, "venv", source, f"python3 -m venv --system-site-packages {venv}", 120)
    active = f"{source}; source {venv}/bin/activate"
    _step(tmp_path, "pip install", active, f"python -m pip install -q {clone}", 1200)
    usage = _step(tmp_path, "planner-host --help", active, "planner-host --help", 120)
    assert "usage: planner-host" in usage, usage
    where = _step(
        tmp_path,
        "imports",
        active,
        "command -v planner-host; python -c 'import nav2_pyif, geometry_msgs; "
        "print(nav2_pyif.__file__); print(geometry_msgs.__file__)'",
        120,
    ).split()
    assert where[0] == f"{venv}/bin/planner-host", where
    assert where[1].startswith(f"{venv}/"), where  # the pip install, not the clone or a workspace
    assert not where[2].startswith(f"{venv}/"), where  # ROS 2's own messages, through the venv
