"""The runner's simulated laser and debug outputs: a controller that
needs input "scan" drives offline with ``--scan``, the scan shipped as the plugin ships a
topic of its ``inputs`` parameter (also inside the goal check's carried query); the reference
controllers' debug outputs come back when asked for and are drawn in the PNG."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from nav2_pyif.runner.laser import LaserSpec
from nav2_pyif.runner.plot import draw
from nav2_pyif.runner.sensing import SensingConfig
from nav2_pyif.testing import assert_reaches_goal, drive

from tests.conftest import FIXTURES

pytestmark = pytest.mark.integration

# A short route on the office map: out of the start room, round the corner and north.
START, GOAL = (2.0, 2.5, 0.0), (3.2, 5.5, 1.5708)
SCAN = SensingConfig(LaserSpec(beams=180, noise=0.01), scan_rate=10.0, debug_every=1.0)


def test_a_scan_based_controller_drives_on_the_simulated_laser(tmp_path: Path) -> None:
    result = drive(
        "sensor_planners:ScanGuard",
        map="office",
        start=START,
        goal=GOAL,
        path=[str(FIXTURES)],
        sensing=SCAN,
        plugins={"goal_checker": "stopped_goal_checker"},  # the scan rides the carried call
    )
    assert_reaches_goal(result)
    assert abs(result.scans - result.cycles / 2) <= 1  # 10 Hz scans, 20 Hz cycles
    carried, alone = result.carried
    assert carried > 10 * alone  # the inputs did not make the cycle fall back to two queries
    carrots = [lines for _, name, lines in result.debug if name == "lookahead_point"]
    assert len(carrots) >= result.sim_time - 1 and all(c[0].shape == (1, 2) for c in carrots)
    draw(result, tmp_path / "scan.png")


def test_without_scan_the_controller_says_what_it_misses() -> None:
    result = drive(
        "sensor_planners:ScanGuard", map="office", start=START, goal=GOAL, path=[str(FIXTURES)]
    )
    assert not result.reached and result.scans == 0
    assert result.outcome.startswith("controller failed: NoValidControl")
    assert "no scan yet" in result.outcome


def test_reference_controllers_return_their_debug_outputs_when_asked() -> None:
    sensing = SensingConfig(debug_every=0.5)
    mppi = drive(
        "mppi",
        map="office",
        start=START,
        goal=GOAL,
        sensing=sensing,
        controller_params={"batch_size": 200, "time_steps": 30},
        timeout=3.0,
    )
    by_name: dict[str, list[list[np.ndarray]]] = {}
    for _, name, lines in mppi.debug:
        by_name.setdefault(name, []).append(lines)
    assert set(by_name) == {"trajectories", "local_plan"}
    times = [t for t, name, _ in mppi.debug if name == "trajectories"]
    assert len(times) >= 6 and np.allclose(np.diff(times), 0.5)  # every 0.5 s of the 3 s run
    assert all(len(lines) == 40 and lines[0].shape == (30, 2) for lines in by_name["trajectories"])
    assert all(len(lines) == 1 and lines[0].shape == (30, 2) for lines in by_name["local_plan"])
    rpp = drive("pure_pursuit", map="office", start=START, goal=GOAL, timeout=2.0)
    assert {name for _, name, _ in rpp.debug} == {"lookahead_point"}
    none = drive(
        "pure_pursuit", map="office", start=START, goal=GOAL, timeout=2.0,
        sensing=SensingConfig(debug_every=0.0),
    )  # fmt: skip
    assert none.debug == []


def test_the_command_takes_the_scan_flags(tmp_path: Path) -> None:
    out = subprocess.run(
        [
            sys.executable, "-m", "nav2_pyif.tools.main", "sim",
            "--controller", "sensor_planners:ScanGuard", "--scan", "--scan-beams", "90",
            "--scan-range", "4", "--scan-rate", "5", "--start", *map(str, START),
            "--goal", *map(str, GOAL), "--out", str(tmp_path), "--name", "guard",
        ],
        capture_output=True, text=True, timeout=120,
        cwd=FIXTURES,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr[-2000:]
    assert "simulated scans: 90 beams" in out.stdout
    summary = json.loads((tmp_path / "guard.json").read_text())["summary"]
    assert summary["scans"] > 0 and summary["debug_outputs"] == {
        "lookahead_point": summary["debug_outputs"]["lookahead_point"]
    }
    bad = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--scan", "--scan-beams", "0"],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert bad.returncode == 2 and "--scan-beams: expected an integer >= 1" in bad.stderr
