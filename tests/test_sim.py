"""The offline runner and the reference planners: every reference controller reaches the goal
on both bundled maps with the A* plan, through a real planner host over Zenoh."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path

import numpy as np
import pytest
from nav2_pyif.sim.inflation import inflate, window
from nav2_pyif.sim.mapfile import (
    FREE,
    OCCUPIED,
    UNKNOWN,
    MapError,
    OccupancyMap,
    load_map,
    read_pgm,
)
from nav2_pyif.sim.report import format_report, summary
from nav2_pyif.testing import assert_reaches_goal, drive
from nav2_pyif_planners.maps import BUNDLED, map_path

NO_JAX = pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif[jax])")
CONTROLLERS = ["pure_pursuit", "apf", "mppi", pytest.param("mppi_jax", marks=NO_JAX)]


@pytest.mark.parametrize("map_name", BUNDLED)
@pytest.mark.parametrize("controller", CONTROLLERS)
def test_reference_controller_reaches_the_goal(controller: str, map_name: str) -> None:
    result = drive(controller, map=map_name)
    print(format_report(result))  # the run's figures, shown with -s or on failure
    assert_reaches_goal(result, min_clearance=0.05, max_time=150.0)
    s = summary(result)
    straight = math.dist(result.start[:2], result.goal[:2])
    assert s["plan_length_m"] > straight  # the maps force detours
    assert 0.8 * s["plan_length_m"] < s["driven_distance_m"] < 1.3 * s["plan_length_m"]
    ops = {r.op for r in result.records}
    assert {"configure", "create_plan", "set_plan", "compute_velocity_commands"} <= ops
    # the rolling local costmap changed at 5 Hz: sent then, not on every 20 Hz cycle
    cycles = [r for r in result.records if r.op == "compute_velocity_commands"]
    with_map = [r for r in cycles if r.request_bytes > 10_000]
    assert 0.1 * len(cycles) < len(with_map) < 0.4 * len(cycles)


def test_the_main_command_writes_png_and_json(tmp_path: Path) -> None:
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "nav2_pyif.tool",
            "sim",
            "--map",
            "office",
            "--out",
            str(tmp_path),
            "--name",
            "run",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr + result.stdout
    assert "REACHED: goal reached" in result.stdout
    assert "compute_velocity_commands" in result.stdout  # the latency table
    png = (tmp_path / "run.png").read_bytes()
    assert png.startswith(b"\x89PNG") and len(png) > 20_000
    record = json.loads((tmp_path / "run.json").read_text())
    assert record["summary"]["reached"] is True
    assert record["summary"]["collisions"] == 0
    assert len(record["trajectory"]) == record["summary"]["cycles"]


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tool", "sim", "--no-progress", *args],
        capture_output=True,
        text=True,
        timeout=120,
        env=dict(os.environ),
    )


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--map", "/nonexistent/map.yaml"], "does not exist"),
        (
            ["--map", "office", "--start", "0.05", "0.05", "0"],
            "start (0.05, 0.05) is inside an obstacle",
        ),
        (["--map", "office", "--goal", "50", "5", "0"], "goal (50.0, 5.0) is outside the map"),
        (
            ["--controller", "no_such_pkg.mod:Ctl", "--timeout", "5"],
            "No module named 'no_such_pkg'",
        ),
        (["--controller", "nonsense"], "unknown planner 'nonsense'"),
    ],
)
def test_bad_input_gets_a_clear_error_and_exit_2(args: list[str], words: str) -> None:
    result = run_cli(*args)
    assert result.returncode == 2, result.stdout + result.stderr
    assert words in result.stderr


def test_an_unreadable_pgm_is_a_clear_error(tmp_path: Path) -> None:
    (tmp_path / "m.pgm").write_bytes(b"P5\n10 10\n255\n" + b"\x00" * 20)
    (tmp_path / "m.yaml").write_text(
        "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
        "nav2_pyif: {start: [0.5, 0.5], goal: [0.8, 0.8]}\n"
    )
    result = run_cli("--map", str(tmp_path / "m.yaml"))
    assert result.returncode == 2 and "truncated" in result.stderr


def test_map_server_format_orientation_and_thresholds(tmp_path: Path) -> None:
    # 3 x 2 image: top row black (occupied), bottom row white / grey (free / unknown)
    (tmp_path / "m.pgm").write_bytes(b"P2\n3 2\n255\n0 0 0\n254 128 254\n")
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 0.5\norigin: [-1.0, 2.0, 0]\n")
    world = load_map(tmp_path / "m.yaml")
    assert world.occupancy.tolist() == [[FREE, UNKNOWN, FREE], [OCCUPIED] * 3]  # row 0 = bottom
    assert (world.origin_x, world.origin_y, world.resolution) == (-1.0, 2.0, 0.5)
    assert read_pgm(tmp_path / "m.pgm").shape == (2, 3)
    with pytest.raises(MapError, match="missing key"):
        (tmp_path / "bad.yaml").write_text("image: m.pgm\n")
        load_map(tmp_path / "bad.yaml")


def test_inflation_follows_nav2s_formula() -> None:
    grid = np.zeros((1, 41), np.int8)
    grid[0, 0] = OCCUPIED
    costmap = inflate(
        OccupancyMap(grid, 0.05, 0.0, 0.0),
        inscribed_radius=0.15,
        inflation_radius=0.55,
        cost_scaling_factor=3.0,
    )
    costs = costmap.data[0]
    assert costs[0] == 254 and costs[1] == costs[3] == 253  # d = 0.05 .. 0.15: inscribed
    for cell in (4, 6, 11):
        d = cell * 0.05
        assert costs[cell] == math.floor(252 * math.exp(-3.0 * (d - 0.15)))
    assert costs[12] == 0  # beyond 0.55 m


def test_rolling_window_is_snapped_and_reads_unknown_outside() -> None:
    costmap = inflate(load_map(map_path("office")))
    local = window(costmap, 0.5, 0.5, 2.0, version=3)
    assert local.size_x == local.size_y == 40 and local.version == 3
    assert local.origin_x == pytest.approx(-0.5) and local.origin_y == pytest.approx(-0.5)
    assert local.cost_at_world(-0.25, 0.5) == 255  # outside the map
    assert local.cost_at_world(0.05, 0.5) == costmap.cost_at_world(0.05, 0.5) == 254  # wall


def test_bundled_maps_have_their_tasks() -> None:
    for name in BUNDLED:
        world = load_map(map_path(name))
        assert world.start is not None and world.goal is not None


def test_a_misspelt_controller_parameter_is_a_warning(tmp_path: Path) -> None:
    result = subprocess.run(
        [
            *(sys.executable, "-m", "nav2_pyif.tool", "sim", "--timeout", "1", "--no-progress"),
            *("--param", "desired_linear_velocity=0.4", "--out", str(tmp_path)),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode in (0, 1), result.stderr
    assert (
        "[WARNING] [nav2_pyif.client] FollowPath: the planner ignores parameter(s) "
        "desired_linear_velocity: desired_linear_velocity is not a parameter of this planner "
        "(did you mean desired_linear_vel?); it declares: approach_velocity_scaling_dist, "
    ) in result.stderr
