"""What each planner of ``nav2-pyif-bench fleet`` needs: its class, the parameters each robot
configures it with, the plan, the costmap and the inputs of each control cycle. The robot
stands still 1 m into a 5 m straight plan on a free 5 m x 5 m rolling costmap (Nav2's local
costmap), so that every cycle does the planner's full work (never the turn in place at the
goal)."""

from __future__ import annotations

import functools
import itertools
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

PLANNERS = {
    "trivial": "nav2_pyif_bench.planners:TrivialController",
    "learned": "nav2_pyif_planners.learned.controller:LearnedController",
    "mppi_jax": "nav2_pyif_planners.mppi_jax:MPPIJax",
    "mppi_nav2": "nav2_pyif_planners.mppi_nav2:Nav2MPPI",
}


@dataclass
class FleetPlanner:
    name: str
    params: dict[str, Any] = field(default_factory=dict)
    scan: bool = False  # send a laser scan with every cycle (the learned controller's input)

    @property
    def spec(self) -> str:
        return PLANNERS[self.name]


def fleet_planner(name: str, robots: int, rollouts: int, workdir: Path) -> FleetPlanner:
    """``name``'s set-up for ``robots`` robots (its batch shapes compiled up to that many)."""
    if name == "mppi_jax":
        return FleetPlanner(name, {"batch_size": rollouts, "fleet_size": robots})
    if name == "mppi_nav2":  # Nav2 Jazzy's FollowPath MPPI block, as mppi-fleet runs it
        from nav2_pyif_planners.mppi_nav2 import nav2_jazzy_params

        params = {k: v for k, v in nav2_jazzy_params().items() if k != "plugin"}
        return FleetPlanner(name, {**params, "batch_size": rollouts})
    if name == "learned":
        weights = untrained_policy(workdir / "policy.npz")
        return FleetPlanner(name, {"weights": str(weights), "fleet_size": robots}, scan=True)
    return FleetPlanner(name)


def untrained_policy(path: Path) -> Path:
    """A policy of the learned controller's shape with random weights: a forward pass costs
    what a trained one's does (timing only; ``nav2-pyif learn`` trains a real one)."""
    from nav2_pyif_planners.learned.features import SIZE
    from nav2_pyif_planners.learned.policy import HIDDEN, Policy

    rng = np.random.default_rng(0)
    sizes = (SIZE, *HIDDEN, 2)
    layers = [
        (rng.normal(0, 1 / np.sqrt(a), (a, b)).astype(np.float32), np.zeros(b, np.float32))
        for a, b in itertools.pairwise(sizes)
    ]
    ones = np.ones(SIZE, np.float32)
    Policy(layers, 0 * ones, ones, np.array([0.5, 1.0], np.float32)).save(path)
    return path


def plan() -> Any:
    from nav2_pyif import Plan

    x = np.linspace(0.0, 5.0, 100)
    return Plan(np.column_stack([x, np.zeros_like(x), np.zeros_like(x)]), "odom")


def costmap() -> Any:
    from nav2_pyif import Costmap

    footprint = [[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]
    return Costmap(
        np.zeros((100, 100), np.uint8), 0.05, origin_x=-1.5, origin_y=-2.5, version=1,
        footprint=footprint,
    )  # fmt: skip


def robot_pose() -> Any:
    from geometry_msgs.msg import PoseStamped

    pose = PoseStamped()
    pose.header.frame_id = "odom"
    pose.pose.position.x = 1.0
    pose.pose.orientation.w = 1.0
    return pose


@functools.cache
def scan() -> Any:
    """A 360-beam LaserScan, as the runner's simulated laser gives the learned controller;
    built once per client process (the C++ plugin passes each scan's bytes as they came)."""
    from sensor_msgs.msg import LaserScan

    msg = LaserScan(angle_min=-np.pi, angle_max=np.pi, range_min=0.05, range_max=12.0)
    msg.angle_increment = 2 * np.pi / 360
    msg.header.frame_id = "base_scan"
    msg.ranges = np.random.default_rng(1).uniform(0.5, 6.0, 360).astype(np.float32).tolist()
    return msg


def workdir() -> Path:
    return Path(tempfile.mkdtemp(prefix="nav2_pyif_fleet_"))
