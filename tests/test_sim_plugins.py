"""The runner with Nav2's other plugins: a smoother, a goal checker and a
progress checker, a costmap layer, each served by a real planner host over Zenoh."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from nav2_pyif.costmap import Costmap
from nav2_pyif.runner.extras import _cells_of
from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.run import SimConfig, run_sim

pytestmark = pytest.mark.integration

#: Across the office corridor's upper half, on the plan A* makes without it.
KEEPOUT = "[[[11, 7.0], [12, 7.0], [12, 8], [11, 8]]]"
ALL_FOUR = {
    "smoother": "simple_smoother",
    "goal_checker": "stopped_goal_checker",
    "progress_checker": "simple_progress_checker",
    "layer": "keepout",
}


def test_all_four_plugins_drive_a_run_to_the_goal() -> None:
    config = SimConfig(
        map=map_path("office"),
        plugins=dict(ALL_FOUR),
        plugin_params={"layer": {"polygons": KEEPOUT}},
    )
    result = run_sim(config)
    assert result.reached, result.outcome
    assert "said stopped_goal_checker" in result.outcome
    # every cycle's goal check carried the progress check and the command (section 15)
    carried, alone = result.carried
    assert (carried, alone) == (2 * result.cycles, 0)
    assert not any(r.op == "compute_velocity_commands" for r in result.records)
    # the layer's cells are in the costmap the planner got, and the plan goes around them
    assert result.layer is not None and result.layer.cells.sum() > 300
    rows, cols = np.nonzero(result.layer.cells)
    assert (result.global_costmap.data[rows, cols] == Costmap.LETHAL).all()
    for x, y in result.plan[:, :2]:
        cell = result.global_costmap.world_to_map(x, y)
        assert cell is not None and not result.layer.cells[cell[1], cell[0]]
    assert not (result.plan[:, 1] > 6.9)[(result.plan[:, 0] > 11) & (result.plan[:, 0] < 12)].any()
    # the smoother changed the planner's path, and kept its ends
    assert result.raw_plan is not None and result.raw_plan.shape != (0, 3)
    assert not np.array_equal(result.raw_plan, result.plan)
    np.testing.assert_allclose(result.raw_plan[[0, -1], :2], result.plan[[0, -1], :2])


def test_the_progress_checker_ends_a_run_that_stalls() -> None:
    config = SimConfig(
        map=map_path("office"),
        plugins={"progress_checker": "simple_progress_checker"},
        plugin_params={
            "progress_checker": {"required_movement_radius": 3.0, "movement_time_allowance": 2.0}
        },
    )
    result = run_sim(config)
    assert not result.reached
    assert result.outcome == "failed to make progress (said simple_progress_checker)"
    assert 2.0 < result.sim_time < 4.0  # stamps are simulated time: the allowance, then a cycle
    assert sum(r.op == "check" for r in result.records) == result.cycles + 1


def test_layer_bounds_become_the_master_cells_that_cover_them() -> None:
    costmap = Costmap(np.zeros((100, 200), np.uint8), 0.05, origin_x=1.0, origin_y=-1.0)
    window = _cells_of((2.02, -0.5, 3.0, 10.0), costmap)
    assert (window.min_i, window.min_j, window.max_i, window.max_j) == (20, 10, 40, 100)
    nothing = _cells_of((np.inf, np.inf, -np.inf, -np.inf), costmap)
    assert nothing.shape == (0, 0)


def test_the_command_line_takes_the_plugins_and_draws_them(tmp_path: Path) -> None:
    result = subprocess.run(
        [
            *(sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--no-progress"),
            *("--out", str(tmp_path), "--name", "run"),
            *("--smoother", "simple_smoother", "--layer", "keepout"),
            *("--layer-param", f"polygons={KEEPOUT}", "--smoother-param", "w_smooth=0.4"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr
    assert "smoothed by simple_smoother" in result.stderr
    assert "smoother simple_smoother, layer keepout" in result.stdout
    summary = json.loads((tmp_path / "run.json").read_text())["summary"]
    assert summary["plugins"] == {"smoother": "simple_smoother", "layer": "keepout"}
    assert summary["layer_cells"] > 300 and summary["raw_plan_length_m"] > 20
    assert (tmp_path / "run.png").stat().st_size > 50_000


@pytest.mark.parametrize("flag", ["--smoother", "--goal-checker", "--progress-checker", "--layer"])
def test_an_unknown_plugin_name_is_refused_with_the_names(flag: str, tmp_path: Path) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", "sim", flag, "nope", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 2
    assert "unknown planner 'nope': give one of" in result.stderr
    assert "keepout" in result.stderr
