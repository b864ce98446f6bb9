"""The offline runner and the reference planners: every reference controller reaches the goal
on both bundled maps with the A* plan, through a real planner host over Zenoh."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import nav2_pyif
import nav2_pyif_protocol
import numpy as np
import pytest
from nav2_pyif.runner.aliases import planner_aliases
from nav2_pyif.runner.inflation import inflate, window
from nav2_pyif.runner.mapfile import (
    FREE,
    OCCUPIED,
    UNKNOWN,
    MapError,
    OccupancyMap,
    load_map,
    read_pgm,
)
from nav2_pyif.runner.maps import BUNDLED, map_path
from nav2_pyif.runner.plot import figure
from nav2_pyif.runner.report import format_report, summary
from nav2_pyif.runner.run import SimConfig, prepare
from nav2_pyif.testing import assert_reaches_goal, drive

from tests.conftest import FIXTURES, free_port
from tests.test_host_e2e import controller

pytestmark = pytest.mark.integration

NO_JAX = pytest.mark.skipif(
    find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])"
)
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
            "nav2_pyif.tools.main",
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


def run_cli(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--no-progress", *args],
        capture_output=True,
        text=True,
        timeout=120,
        env=dict(os.environ, **(env or {})),
    )


def test_connect_names_the_run_after_what_the_host_serves(
    start_host: Any, zsession_factory: Any, tmp_path: Path
) -> None:
    host = start_host(
        *("--serve", "nav2_pyif/sim/FollowPath=nav2_pyif_planners.mppi:MPPI"),
        *("--serve", "nav2_pyif/sim/GridBased=nav2_pyif_planners.astar:AStar"),
    )
    controller(zsession_factory, host, key="nav2_pyif/sim/FollowPath")  # waits until it serves
    short = ("--connect", host.endpoint, "--timeout", "1", "--out", str(tmp_path))
    result = run_cli(*short)
    assert result.returncode == 1, result.stderr  # 1 s: not there yet
    record = json.loads((tmp_path / "office_mppi.json").read_text())
    assert (record["summary"]["controller"], record["summary"]["planner"]) == ("mppi", "astar")
    assert record["summary"]["served"]["controller"] == "nav2_pyif_planners.mppi:MPPI"
    assert "controller mppi, planner astar" in result.stdout
    assert (tmp_path / "office_mppi.png").exists()
    assert not (tmp_path / "office_pure_pursuit.png").exists()
    assert "--controller" not in result.stderr  # nothing asked, nothing to contradict

    result = run_cli(*short, "--controller", "pure_pursuit", "--name", "asked")
    assert "--controller pure_pursuit was given, but the host at" in result.stderr
    assert "serves nav2_pyif_planners.mppi:MPPI on nav2_pyif/sim/FollowPath" in result.stderr
    assert json.loads((tmp_path / "asked.json").read_text())["summary"]["controller"] == "mppi"


def test_help_lists_every_reference_planner_and_bundled_map() -> None:
    result = run_cli("--help")
    assert result.returncode == 0
    for name, target in planner_aliases().items():
        assert re.search(rf"^  {name} +{re.escape(target)}", result.stdout, re.M), name
    for name in BUNDLED:
        assert name in result.stdout


def test_an_unknown_map_name_lists_the_bundled_maps() -> None:
    result = run_cli("--map", "offfice")
    assert result.returncode == 2
    assert f"the bundled maps: {', '.join(BUNDLED)}" in result.stderr


def test_missing_jax_names_a_command_that_installs_it(tmp_path: Path) -> None:
    (tmp_path / "jax").mkdir()  # a jax that fails to import, as a missing one does
    (tmp_path / "jax/__init__.py").write_text("raise ImportError(\"No module named 'jax'\")\n")
    path = os.pathsep.join([str(tmp_path), os.environ.get("PYTHONPATH", "")])
    for alias in ("mppi_jax", "mppi_nav2"):
        result = run_cli("--controller", alias, env={"PYTHONPATH": path})
        assert result.returncode == 2  # the host could not load the planner: a usage error
        assert f"{sys.executable} -m pip install 'jax>=0.4.30'" in result.stderr
        assert "NAV2_PYIF_EXTRAS=dev,jax ./scripts/bootstrap.sh" in result.stderr


def test_the_picture_has_a_cost_scale_a_heading_legend_and_wrapped_titles() -> None:
    long_name = "my_robot_planners.controllers.go_to:GoToTheGoalController"
    result = prepare(SimConfig(map=map_path("office"), controller=long_name))
    result.trajectory = [(0.05 * i, 2.0 + 0.02 * i, 2.5, 0.0, 0.4, 0.0) for i in range(40)]
    result.outcome, result.interrupted = "interrupted by SIGTERM", "SIGTERM"
    fig = figure(result)
    try:
        bars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
        assert len(bars) == 1 and "cost" in bars[0].get_ylabel()
        world = fig.axes[0]
        legend = world.get_legend()
        assert legend is not None
        assert "heading" in [t.get_text() for t in legend.get_texts()]
        title = world.get_title()
        assert "interrupted by SIGTERM" in " ".join(title.split()) and "\n" in title
        assert max(map(len, title.splitlines())) <= 90
    finally:
        plt.close(fig)


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
        (["--param", "lookahead=[1,"], "--param 'lookahead=[1,': the value is not YAML"),
        (["--layer-param", "polygons=[[1,"], "--layer-param 'polygons=[[1,': the value is not"),
        (["--planner-param", "tolerance"], "--planner-param 'tolerance' is not NAME=VALUE"),
    ],
)
def test_bad_input_gets_a_clear_error_and_exit_2(args: list[str], words: str) -> None:
    result = run_cli(*args)
    assert result.returncode == 2, result.stdout + result.stderr
    assert words in result.stderr
    assert "Traceback" not in result.stderr


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


def run_sim_command(
    out: Path, *args: str, planners: Path = FIXTURES
) -> subprocess.CompletedProcess[str]:
    """``nav2-pyif sim`` on the office map, planners from ``planners`` (the test fixtures),
    output in ``out``."""
    sim = [sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--no-progress", "--out", str(out)]
    return subprocess.run(
        [*sim, "--path", str(planners), *args], capture_output=True, text=True, timeout=120
    )


def test_a_planner_failing_to_configure_shows_its_own_traceback_first(tmp_path: Path) -> None:
    # the planner's folder has "nav2_pyif" in its path, as in a clone of that name
    own = tmp_path / "nav2_pyif" / "my_planners"
    own.mkdir(parents=True)
    shutil.copy(FIXTURES / "user_faults.py", own)
    result = run_sim_command(tmp_path, "--controller", "user_faults:BrokenConfigure", planners=own)
    assert result.returncode == 1
    report = result.stdout.splitlines()
    assert report[0] == "Traceback (most recent call last):", result.stdout
    tb = report[: report.index("")]
    source = (FIXTURES / "user_faults.py").read_text().splitlines()
    calls, raises = (
        next(n for n, line in enumerate(source, 1) if text in line)
        for text in ("self.load_model()", 'raise RuntimeError("my configure is broken")')
    )
    assert f'user_faults.py", line {calls}, in configure' in tb[1]
    assert f'user_faults.py", line {raises}, in load_model' in tb[3]
    assert tb[-1] == "RuntimeError: my configure is broken"
    host_code = [str(Path(m.__file__ or "").parent) for m in (nav2_pyif, nav2_pyif_protocol)]
    assert str(own) in tb[1]
    assert not [line for line in tb if any(code in line for code in host_code)]
    assert report[len(tb) + 1].startswith(
        "NOT REACHED: user_faults:BrokenConfigure could not start, so the run stopped: "
        "InvalidController"
    )
    record = json.loads((tmp_path / "office_user_faults.BrokenConfigure.json").read_text())
    assert f"line {raises}, in load_model" in record["traceback"]


def test_a_timeout_is_a_result_not_a_crash(tmp_path: Path) -> None:
    # real time: lockstep would wait for the slow set_plan
    result = run_sim_command(tmp_path, "--controller", "user_faults:SlowSetPlan", "--realtime")
    assert result.returncode == 1, result.stderr  # not reached; no traceback of the runner
    assert "Traceback" not in result.stderr
    # as in Nav2: the plan the host failed is owed, and the cycle that sends it first fails
    outcome = "controller failed: NoValidControl: set_plan got no reply"
    assert f"NOT REACHED: {outcome}" in result.stdout
    record = json.loads((tmp_path / "office_user_faults.SlowSetPlan.json").read_text())
    assert record["summary"]["outcome"].startswith(outcome)


def test_a_recovery_behaviour_runs_when_the_controller_keeps_failing(tmp_path: Path) -> None:
    """As Nav2's behaviour tree: past the failure tolerance, a BackUp (the Python
    FreestBackUp, served by the host), then the controller follows the plan again."""
    stuck = ("--controller", "user_faults:StuckUntilMoved", "--timeout", "60")
    alone = run_sim_command(tmp_path / "alone", *stuck)
    assert alone.returncode == 1, alone.stderr
    assert re.search(r"NOT REACHED: controller failed: NoValidControl: .*stuck here", alone.stdout)

    recovered = run_sim_command(tmp_path / "recovered", *stuck, "--recovery", "free_backup")
    assert recovered.returncode == 0, recovered.stdout + recovered.stderr
    assert "REACHED" in recovered.stdout.splitlines()[0]
    assert re.search(r"recoveries by free_backup: 1 \(t=0\.\d s succeeded", recovered.stdout)
    name = "office_user_faults.StuckUntilMoved_free_backup.json"
    record = json.loads((tmp_path / "recovered" / name).read_text())
    (backup,) = record["summary"]["recoveries"]
    assert backup["outcome"] == "succeeded" and backup["seconds"] > 1.0  # 0.3 m at 0.15 m/s
    moved = [row for row in record["trajectory"] if row[0] <= backup["t_s"] + backup["seconds"]]
    start = record["trajectory"][0]
    assert math.dist(moved[-1][1:3], start[1:3]) > 0.25  # the behaviour drove the robot


def test_built_in_zenoh_configs_make_no_shared_memory_pool_on_the_first_large_message() -> None:
    # eclipse-zenoh's default made the first message above 3 kB (the first plan) cost 10-20 ms
    from nav2_pyif.common.zenoh_config import ZenohOptions, build_config

    for options in (ZenohOptions(use_environment=False), ZenohOptions(listen=["tcp/[::1]:0"])):
        config = build_config(options)
        assert json.loads(config.get_json("transport/shared_memory/enabled")) is False


def test_a_misspelt_controller_parameter_is_a_warning(tmp_path: Path) -> None:
    result = subprocess.run(
        [
            *(
                sys.executable,
                "-m",
                "nav2_pyif.tools.main",
                "sim",
                "--timeout",
                "1",
                "--no-progress",
            ),
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


def test_a_run_that_cannot_reach_its_host_fails_with_1_not_the_usage_code() -> None:
    """A connection nothing answers is the run failing, not bad arguments (2)."""
    result = run_cli("--connect", f"tcp/127.0.0.1:{free_port()}", "--wait", "1")
    assert result.returncode == 1, result.stdout + result.stderr
    assert "nav2-pyif sim: error:" in result.stderr and "Traceback" not in result.stderr
