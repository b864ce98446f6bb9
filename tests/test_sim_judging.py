"""The runner judges a run as Nav2 does: the goal check on the plan's last pose (where
controller_server's goal checker looks), and an outcome that says which check ended the run.
Real hosts over Zenoh."""

from __future__ import annotations

from typing import Any

import pytest
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
