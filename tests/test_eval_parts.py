"""The parts of ``nav2-pyif eval`` that need no process: generated scenarios, the optimal
path, BARN's score, jerk, the summary."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from nav2_pyif.evaluation.compare import compare
from nav2_pyif.evaluation.metrics import COMPUTE_FIELDS, barn_score, jerk_rms
from nav2_pyif.evaluation.report import summarize, without_compute
from nav2_pyif.evaluation.scenarios import (
    GENERATED_GOAL,
    GENERATED_START,
    ScenarioError,
    from_map,
    generated,
    shortest_path_length,
)
from nav2_pyif.runner.mapfile import FREE, OCCUPIED, OccupancyMap, load_map

pytestmark = pytest.mark.unit


def test_a_generated_world_is_the_same_from_the_same_seed_and_crossable(tmp_path: Path) -> None:
    a = generated(3, seed=7, density=0.2, folder=tmp_path / "a")
    b = generated(3, seed=7, density=0.2, folder=tmp_path / "b")
    other = generated(4, seed=7, density=0.2, folder=tmp_path / "a")
    assert a.map.with_suffix(".pgm").read_bytes() == b.map.with_suffix(".pgm").read_bytes()
    assert a.map.with_suffix(".pgm").read_bytes() != other.map.with_suffix(".pgm").read_bytes()
    world = load_map(a.map)
    assert (world.start, world.goal) == (GENERATED_START, GENERATED_GOAL)
    straight = math.dist(GENERATED_START[:2], GENERATED_GOAL[:2])
    assert a.optimal_length is not None and a.optimal_length >= straight - 0.05
    # the density asked for, between start and goal (the boxes may overshoot by one box)
    region = world.occupancy[:, round(1.5 / 0.05) : round(6.5 / 0.05)]
    assert 0.2 <= np.count_nonzero(region == OCCUPIED) / region.size < 0.3


def test_a_density_out_of_range_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ScenarioError, match=r"--density 1: give a fraction in \[0, 1\)"):
        generated(0, seed=0, density=1.0, folder=tmp_path)


def test_the_optimal_path_goes_round_a_wall_and_none_crosses_a_closed_one() -> None:
    grid = np.full((60, 100), FREE, np.int8)  # 5 m x 3 m at 5 cm
    grid[0:40, 48:52] = OCCUPIED  # a wall from the bottom, open above y = 2 m
    world = OccupancyMap(grid, 0.05, 0.0, 0.0)
    start, goal = (1.0, 0.5, 0.0), (4.0, 0.5, 0.0)
    length = shortest_path_length(world, start, goal)
    # over the wall's top corner, the robot's inscribed radius (0.15 m) clear of it; an
    # 8-connected grid path is at most 8 % longer than the straight lines
    over = 2 * math.hypot(1.5, 2.0 + 0.15 - 0.5)
    assert length is not None and over - 0.05 < length < over * 1.09
    grid[:, 48:52] = OCCUPIED
    assert shortest_path_length(world, start, goal) is None


def test_a_user_map_without_a_task_needs_start_and_goal(tmp_path: Path) -> None:
    (tmp_path / "mine.pgm").write_bytes(b"P5\n4 4\n255\n" + bytes([254]) * 16)
    (tmp_path / "mine.yaml").write_text("image: mine.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n")
    with pytest.raises(ScenarioError, match="give --start and --goal"):
        from_map(str(tmp_path / "mine.yaml"), None, None)
    scenario = from_map(str(tmp_path / "mine.yaml"), (0.2, 0.2, 0.0), (1.7, 1.7, 0.0))
    assert scenario.name == "mine" and scenario.goal == (1.7, 1.7, 0.0)


def test_barn_score_is_barns_formula() -> None:
    # optimal time 10 m / 2 m/s = 5 s; the time taken is clipped to [20 s, 40 s]
    assert barn_score(True, 30.0, 10.0, 2.0) == pytest.approx(5 / 30)
    assert barn_score(True, 12.0, 10.0, 2.0) == pytest.approx(5 / 20)
    assert barn_score(True, 90.0, 10.0, 2.0) == pytest.approx(5 / 40)
    assert barn_score(False, 30.0, 10.0, 2.0) == 0.0
    assert barn_score(True, 30.0, None, 2.0) is None


def test_jerk_is_the_rms_of_the_speeds_second_difference() -> None:
    dt = 0.05
    steady = [(i * dt, 0.0, 0.0, 0.0, 0.5, 0.0) for i in range(20)]
    assert jerk_rms(steady, dt, 4) == 0.0
    ramp = [(i * dt, 0.0, 0.0, 0.0, 0.1 * i, 0.0) for i in range(20)]  # constant acceleration
    assert jerk_rms(ramp, dt, 4) == pytest.approx(0.0, abs=1e-9)
    kick = [*steady[:10], (0.5, 0, 0, 0, 0.6, 0), *steady[11:]]  # one step of +0.1 m/s
    assert jerk_rms(kick, dt, 4) == pytest.approx(math.sqrt(6 * (0.1 / dt**2) ** 2 / 18))
    assert jerk_rms(steady[:2], dt, 4) is None


def test_the_summary_and_the_report_less_compute() -> None:
    rows = [
        {"planner": "a", "success": True, "time_to_goal_s": 10.0, "min_clearance_m": 0.0,
         "compute_median_ms": 1.0, "compute_p99_ms": 3.0, "barn_score": 0.2},
        {"planner": "a", "success": False, "time_to_goal_s": None, "min_clearance_m": 0.3,
         "compute_median_ms": 2.0, "compute_p99_ms": 5.0, "barn_score": 0.0},
    ]  # fmt: skip
    (a,) = summarize(rows, ["a"])
    assert (a["success_rate"], a["time_to_goal_s"], a["min_clearance_m"]) == (0.5, 10.0, 0.0)
    assert (a["compute_median_ms"], a["compute_p99_ms"], a["barn_score"]) == (1.5, 5.0, 0.1)
    report = {"settings": {"mode": "lockstep", "workers": 2}, "summary": [a], "runs": rows}
    less = without_compute(report)
    assert not set(COMPUTE_FIELDS) & {k for r in less["runs"] + less["summary"] for k in r}
    assert less["settings"] == {"mode": "lockstep"} and less["runs"][0]["barn_score"] == 0.2


def _report(rows: list[dict[str, Any]], workers: int) -> dict[str, Any]:
    planners = list(dict.fromkeys(r["planner"] for r in rows))
    return {
        "settings": {"mode": "lockstep", "workers": workers},
        "summary": summarize(rows, planners),
        "runs": rows,
    }


def test_compare_finds_only_what_is_not_a_compute_figure() -> None:
    rows = [
        {"planner": p, "scenario": s, "success": True, "time_to_goal_s": 10.0 + i,
         "compute_median_ms": 1.0, "compute_p99_ms": 3.0, "wall_time_s": 4.0}
        for i, (p, s) in enumerate([("a", "office"), ("a", "gen_1"), ("b", "office")])
    ]  # fmt: skip
    idle = _report(rows, workers=2)
    busy = [dict(r, compute_median_ms=9.0, compute_p99_ms=80.0, wall_time_s=30.0) for r in rows]
    assert compare(idle, _report(busy[::-1], workers=1)) == []  # any order, any worker count
    busy[1] = dict(busy[1], success=False, time_to_goal_s=None)
    assert compare(idle, _report(busy, workers=1)) == [
        "summary[a].successes: 2 != 1",
        "summary[a].success_rate: 1.0 != 0.5",
        "summary[a].time_to_goal_s: 10.5 != 10.0",
        "runs[a on gen_1].success: True != False",
        "runs[a on gen_1].time_to_goal_s: 11.0 != None",
    ]
