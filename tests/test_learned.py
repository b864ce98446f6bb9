"""The learned controller end to end on a tiny budget: MPPI demonstrations in
the offline runner (a real host, real Zenoh, the simulated laser through the inputs), JAX
training, the weights saved, and the learned controller driving to the goal the same way."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from nav2_pyif_planners.learned.pipeline import LearnConfig, LearnResult, Task, learn
from nav2_pyif_planners.learned.policy import Policy

from tests.test_batched_planners import PLANNER_KEY, drive_robots, robot_key

pytestmark = pytest.mark.integration

# A short route on the office map: out of the start room, round the corner and north.
ROUTE = Task("office", (2.0, 2.5, 0.0), (3.2, 5.5, 1.5708))


@pytest.fixture(scope="module")
def trained(tmp_path_factory: pytest.TempPathFactory) -> tuple[LearnResult, Path]:
    weights = tmp_path_factory.mktemp("learned") / "user_data" / "policy.npz"
    config = LearnConfig(
        tasks=[ROUTE],
        runs=2,
        steps=800,
        weights=weights,
        evaluate=ROUTE,
        mppi={"batch_size": 300, "time_steps": 30},  # a cheaper expert: the route is easy
        timeout=40.0,
    )
    return learn(config), weights


def test_a_policy_trained_on_mppi_demonstrations_reaches_the_goal(
    trained: tuple[LearnResult, Path],
) -> None:
    result, weights = trained
    assert all(d.reached for d in result.demonstrations), [d.outcome for d in result.demonstrations]
    assert all(d.scans == d.cycles or d.scans == d.cycles + 1 for d in result.demonstrations)
    assert result.training.samples > 300 and result.training.loss < 0.05
    policy = Policy.load(weights)  # what was saved is what drove
    assert policy.layers[0][0].shape[0] == len(policy.mean)
    drive = result.drive
    assert drive is not None and drive.reached, drive and (drive.outcome, drive.controller_errors)
    assert drive.collisions == 0 and drive.served["controller"].endswith("LearnedController")
    # it followed the plan, not a lucky line: never far from it
    plan = drive.plan[:, :2]
    driven = np.array([p[1:3] for p in drive.trajectory])
    gaps = np.min(np.linalg.norm(driven[:, None] - plan[None], axis=2), axis=1)
    assert gaps.max() < 0.5


def test_two_robots_reach_the_goal_with_one_batched_learned_controller(
    trained: tuple[LearnResult, Path], start_host: Any, tmp_path: Path
) -> None:
    _, weights = trained
    names = ["gamma", "delta"]
    learned = "nav2_pyif_planners.learned.controller:LearnedController"
    host = start_host(
        *(f"--serve={robot_key(n)}={learned}" for n in names),
        f"--serve={PLANNER_KEY}=nav2_pyif_planners.astar:AStar",
        "--batch",
    )
    assert ROUTE.start is not None and ROUTE.goal is not None
    start, goal = [str(v) for v in ROUTE.start], [str(v) for v in ROUTE.goal]
    records = drive_robots(
        host,
        names,
        tmp_path,
        *("--map", ROUTE.map, "--start", *start, "--goal", *goal, "--scan"),
        *("--param", f"weights={weights}", "--param", "fleet_size=2"),
    )
    for record in records:
        summary = record["summary"]
        assert summary["reached"] is True and summary["collisions"] == 0, summary
    assert "batch group: " + learned + " serves 2 key(s)" in host.log()
