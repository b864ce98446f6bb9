"""The reference planners' own contracts, in process: A*'s nav2_core errors and plans, the
controllers' speed limits and refusals."""

from __future__ import annotations

import logging
import math
import re
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif import Costmap, Parameters, Plan
from nav2_pyif._context import PluginContext
from nav2_pyif.plugin import PlannerPlugin
from nav2_pyif.runner.inflation import inflate
from nav2_pyif.runner.mapfile import load_map
from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.run import pose_msg
from nav2_pyif_planners.astar import AStar
from nav2_pyif_planners.mppi import MPPI
from nav2_pyif_planners.pure_pursuit import RegulatedPurePursuit

pytestmark = pytest.mark.unit


def attach(planner: PlannerPlugin, costmap: Costmap, **params: Any) -> Any:
    planner._attach(
        PluginContext(
            "P",
            "server",
            "map",
            "base_link",
            costmap,
            Parameters(params),
            logging.getLogger("test"),
        )
    )
    planner.configure()
    return planner


@pytest.fixture(scope="module")
def office() -> Costmap:
    return inflate(load_map(map_path("office")), inscribed_radius=0.15)


def test_astar_plans_around_walls_keeping_off_inflated_cells(office: Costmap) -> None:
    astar = attach(AStar(), office)
    plan = astar.create_plan(pose_msg(2.0, 2.5, 0.0), pose_msg(17.5, 12.0, 1.0), lambda: False)
    assert plan.shape[1] == 3 and np.allclose(plan[0, :2], [2.0, 2.5])
    assert np.allclose(plan[-1], [17.5, 12.0, 1.0])
    costs = office.costs_at_world(plan[:, :2])
    assert costs.max() < Costmap.INSCRIBED
    steps = np.hypot(*np.diff(plan[:, :2], axis=0).T)
    assert steps.max() < 0.15  # dense: about one pose per cell (diagonals 0.07 m)


@pytest.mark.parametrize(
    ("start", "goal", "error"),
    [
        ((0.05, 0.05), (3.0, 3.0), api.StartOccupied),
        ((2.0, 2.5), (5.0, 3.0), api.GoalOccupied),  # on a room divider
        ((-1.0, 2.0), (3.0, 3.0), api.StartOutsideMapBounds),
        ((2.0, 2.5), (3.0, 30.0), api.GoalOutsideMapBounds),
    ],
)
def test_astar_refuses_with_nav2_errors(
    office: Costmap, start: tuple[float, float], goal: tuple[float, float], error: type
) -> None:
    astar = attach(AStar(), office)
    with pytest.raises(error):
        astar.create_plan(pose_msg(*start, 0.0), pose_msg(*goal, 0.0), lambda: False)


def test_astar_no_path_and_cancellation() -> None:
    grid = np.zeros((40, 40), np.uint8)
    grid[:, 20] = Costmap.LETHAL  # a wall with no door
    astar = attach(AStar(), Costmap(grid, 0.1))
    with pytest.raises(api.NoValidPathCouldBeFound, match="no path"):
        astar.create_plan(pose_msg(0.5, 0.5, 0), pose_msg(3.5, 0.5, 0), lambda: False)
    open_map = attach(AStar(), Costmap(np.zeros((300, 300), np.uint8), 0.05))
    with pytest.raises(api.PlannerCancelled):
        open_map.create_plan(pose_msg(0.1, 0.1, 0), pose_msg(14.0, 14.0, 0), lambda: True)


def straight_plan(length: float = 4.0) -> Plan:
    x = np.linspace(0.5, 0.5 + length, 80)
    return Plan(np.column_stack([x, np.full_like(x, 2.0), np.zeros_like(x)]), "map")


def mppi_jax() -> type:
    pytest.importorskip("jax", reason="JAX is not installed (nav2-pyif-planners[jax])")
    from nav2_pyif_planners.mppi_jax import MPPIJax

    return MPPIJax


@pytest.mark.parametrize("make", [lambda: RegulatedPurePursuit, lambda: MPPI, mppi_jax])
def test_controllers_honour_speed_limits(make: Any) -> None:
    free = Costmap(np.zeros((80, 120), np.uint8), 0.05)
    controller = attach(make()(), free)
    controller.set_plan(straight_plan())
    velocity = Twist()
    speeds = []
    for limit in (None, (0.2, False), (50.0, True)):
        if limit is not None:
            controller.set_speed_limit(*limit)
        top = 0.0
        for _ in range(30):
            cmd = controller.compute_velocity_commands(pose_msg(0.6, 2.0, 0.0), velocity, None)
            top = max(top, cmd.twist.linear.x)
        speeds.append(top)
    assert speeds[0] > 0.3
    assert speeds[1] <= 0.2 + 1e-9
    assert speeds[2] <= 0.25 + 1e-9  # 50 % of 0.5 m/s


def test_pure_pursuit_refuses_to_drive_into_a_wall() -> None:
    grid = np.zeros((80, 120), np.uint8)
    grid[:, 30:] = Costmap.LETHAL  # a wall 1.5 m ahead, right across the plan
    controller = attach(
        RegulatedPurePursuit(),
        Costmap(grid, 0.05, footprint=[[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]),
    )
    controller.set_plan(straight_plan())
    fast = Twist()
    fast.linear.x = 0.5
    with pytest.raises(api.NoValidControl, match="collision ahead"):
        controller.compute_velocity_commands(pose_msg(1.1, 2.0, 0.0), fast, None)


def test_controllers_turn_to_the_goal_heading_at_the_goal() -> None:
    free = Costmap(np.zeros((80, 120), np.uint8), 0.05)
    plan = Plan(np.array([[0.5, 2.0, 0.0], [1.0, 2.0, math.pi / 2]]), "map")
    classes: list[type] = [RegulatedPurePursuit, MPPI]
    if find_spec("jax") is not None:
        classes.append(mppi_jax())
    for cls in classes:
        controller = attach(cls(), free)
        controller.set_plan(plan)
        cmd = controller.compute_velocity_commands(pose_msg(0.95, 2.0, 0.0), Twist(), None)
        assert cmd.twist.linear.x == 0.0 and cmd.twist.angular.z > 0.5


def test_the_short_names_the_runner_takes_are_the_reference_planners_entry_points() -> None:
    """`nav2-pyif sim --controller mppi`: nav2-pyif-planners declares each name (group
    nav2_pyif.planners), and each names a planner of its that is there."""
    from importlib.metadata import distribution

    from nav2_pyif.runner.aliases import GROUP, planner_aliases
    from nav2_pyif.runner.run import DEFAULTS

    declared = {
        point.name: point.value
        for point in distribution("nav2-pyif-planners").entry_points
        if point.group == GROUP
    }
    assert set(DEFAULTS.values()) <= set(declared) <= set(planner_aliases())
    for name, target in declared.items():
        module, _, attribute = target.partition(":")
        assert module.startswith("nav2_pyif_planners."), name
        spec = find_spec(module)
        assert spec is not None and spec.origin, f"{name}: no module {module}"
        if attribute:  # defined or imported there; not imported here (JAX's need JAX)
            source = Path(spec.origin).read_text(encoding="utf-8")
            assert re.search(rf"\b{attribute}\b", source), f"{name}: no {attribute} in {module}"
