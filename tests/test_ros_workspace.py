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
    setup = _setup_script(distro, BACKEND)
    if not setup:
        pytest.skip(
            f"the {distro} workspace trial needs a ROS 2 {distro} with Nav2 and zenoh-pico: "
            f"set {_own_variable(distro, BACKEND)} (testenv/build.sh {distro} writes one)"
        )
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
