"""The runner judges a run as Nav2 does: the goal check on the plan's last pose (where
controller_server's goal checker looks), and an outcome that says which check ended the run.
Real hosts over Zenoh."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from nav2_pyif.runner.report import format_report
from nav2_pyif.testing import drive

from tests.conftest import FIXTURES

pytestmark = pytest.mark.integration

# about 8 simulated seconds on the office map
TASK: dict[str, Any] = {"start": (2.0, 2.5, 0.0), "goal": (3.2, 5.5, 1.57), "path": [str(FIXTURES)]}


def test_a_plan_that_stops_short_reaches_its_goal_as_in_nav2() -> None:
    result = drive("pure_pursuit", "short_plans:ShortPlan", timeout=30.0, **TASK)
    assert result.reached, format_report(result)
    assert result.outcome == (
        "goal reached (within xy_goal_tolerance 0.25 m and yaw_goal_tolerance 0.25 rad of the "
        "plan's last pose)"
    )


def test_a_run_that_times_out_says_which_check_it_failed() -> None:
    # a controller too slow to arrive in time: the outcome says how far it still was
    result = drive(
        "pure_pursuit",
        "short_plans:ShortPlan",
        timeout=2.0,
        controller_params={"desired_linear_vel": 0.2},
        **TASK,
    )
    assert not result.reached
    assert result.outcome.startswith(
        "timeout after 2 s: the goal check never passed: the robot is "
    ), result.outcome
    assert (
        "m from the plan's last pose (xy_goal_tolerance 0.25 m); the plan ends 0.40 m from "
        "the goal asked for" in result.outcome
    )


def test_a_start_up_that_outlasts_its_wait_names_the_slow_import() -> None:
    with pytest.raises(TimeoutError) as timed_out:
        drive("slow_import:SlowToImport", startup_wait=10.0, **TASK)
    assert str(timed_out.value).startswith(
        "the planner host was still importing slow_import:SlowToImport after 10 s: a slow "
        "import (torch, jax, a model's weights) needs a longer start-up wait (--startup-wait"
    ), timed_out.value


def sim(cwd: Path, *args: str) -> tuple[subprocess.CompletedProcess[str], dict[str, Any]]:
    """``nav2-pyif sim`` run in ``cwd`` on the short task; its JSON record."""
    start_goal = ("--start", "2", "2.5", "0", "--goal", "3.2", "5.5", "1.57")
    done = subprocess.run(
        [
            *(sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--no-progress"),
            *("--path", str(FIXTURES), *start_goal, "--name", "run", *args),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
    )
    record = cwd / "out" / "run.json"
    return done, json.loads(record.read_text()) if record.exists() else {}


def test_sim_judges_by_the_nav2_params_file_it_finds_here(tmp_path: Path) -> None:
    params = {
        "controller_server": {
            "ros__parameters": {
                "controller_frequency": 10.0,
                "general_goal_checker": {
                    "plugin": "nav2_controller::SimpleGoalChecker",
                    "xy_goal_tolerance": 0.4,
                },
                "goal_checker_plugins": ["general_goal_checker"],
                "FollowPath": {
                    "plugin": "nav2_pyif_bridge::PyController",
                    "python_planner": "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
                    "timeout": 0.1,
                    "desired_linear_vel": 0.25,
                },
            }
        }
    }
    (tmp_path / "nav2_params.yaml").write_text(yaml.safe_dump(params))
    done, record = sim(tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    summary = record["summary"]
    assert summary["params_file"] == "nav2_params.yaml"
    assert summary["controller"] == "pure_pursuit" and summary["control_rate_hz"] == 10.0
    assert summary["timing"]["call_timeout_ms"] == 100.0
    assert "xy_goal_tolerance 0.4 m" in summary["outcome"]
    assert max(row[4] for row in record["trajectory"]) <= 0.25 + 1e-6  # its desired_linear_vel
    assert "Nav2 params from nav2_params.yaml: controller_frequency 10 Hz" in done.stderr


def test_sim_maps_a_module_of_functions_with_delegate(tmp_path: Path) -> None:
    functions = ("--controller", "sim_functions", "--timeout", "2")
    unmapped, _ = sim(tmp_path, *functions)
    assert unmapped.returncode == 2, unmapped.stderr
    assert "defines no function compute_velocity_commands" in unmapped.stderr
    assert "map them with --delegate ROLE=FUNCTION" in unmapped.stderr  # as sim now does
    mapped, record = sim(
        tmp_path, *functions, "--delegate", "compute_velocity_commands=go_straight"
    )
    assert mapped.returncode == 1, mapped.stdout + mapped.stderr  # not reached: straight on
    assert record["summary"]["controller"] == "sim_functions"
    assert max(row[4] for row in record["trajectory"]) == pytest.approx(0.3)
