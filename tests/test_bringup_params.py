"""The stock-bringup launch test's params edit (bridge_plugin/test/nav2/test_bringup.py), which
runs only where Nav2 is built: on params shaped as each distribution's nav2_params.yaml, only
the `plugin:` lines of FollowPath, GridBased and progress_checker change, each followed by
where its host is; nested plugins (MPPI's motion model), comments and every other line stay."""

from __future__ import annotations

import importlib
import sys
from types import ModuleType

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.unit


def _load_test_bringup() -> ModuleType:
    """test_bringup.py with its neighbours (nav2_testing, test_host_recovery) importable, as
    pytest imports it there."""
    sys.path.insert(0, str(ROOT / "bridge_plugin" / "test" / "nav2"))
    return importlib.import_module("test_bringup")


test_bringup = _load_test_bringup()

# Written here in the shape of nav2_bringup's params (Humble's DWB and slash-named NavFn; the
# same server and plugin names on Jazzy and Lyrical), not copied from them.
HUMBLE_SHAPED = """\
controller_server:
  ros__parameters:
    controller_frequency: 20.0
    progress_checker_plugin: "progress_checker"
    progress_checker:
      plugin: "nav2_controller::SimpleProgressChecker"
      required_movement_radius: 0.5
    # precise_goal_checker:
    #   plugin: "nav2_controller::SimpleGoalChecker"
    general_goal_checker:
      plugin: "nav2_controller::SimpleGoalChecker"
    FollowPath:
      plugin: "dwb_core::DWBLocalPlanner"
      critics: ["RotateToGoal", "Oscillation"]
planner_server:
  ros__parameters:
    planner_plugins: ["GridBased"]
    GridBased:
      plugin: "nav2_navfn_planner/NavfnPlanner"
      tolerance: 0.5
"""
LYRICAL_SHAPED = """\
controller_server:
  ros__parameters:
    progress_checker_plugins: ["progress_checker"]
    progress_checker:
      plugin: "nav2_controller::SimpleProgressChecker"
    PathHandler:
      plugin: "nav2_controller::FeasiblePathHandler"
    FollowPath:
      plugin: "nav2_mppi_controller::MPPIController"
      motion_model: "DiffDrive"
      Optimizer:
        plugin: "mppi::DefaultOptimalTrajectoryValidator"
local_costmap:
  local_costmap:
    ros__parameters:
      inflation_layer:
        plugin: "nav2_costmap_2d::InflationLayer"
planner_server:
  ros__parameters:
    GridBased:
      plugin: 'nav2_navfn_planner::NavfnPlanner'
"""


def _served(name: str, planner: str) -> list[str]:
    return [f'key: "robot1/{name}"', f"# {planner}"]


@pytest.mark.parametrize("stock", [HUMBLE_SHAPED, LYRICAL_SHAPED], ids=["humble", "lyrical"])
def test_only_the_three_plugin_lines_change(stock: str) -> None:
    edited = test_bringup.python_params(stock, _served)
    removed = [line for line in stock.splitlines() if line not in edited.splitlines()]
    added = [line for line in edited.splitlines() if line not in stock.splitlines()]
    assert len(removed) == 3, removed
    assert all(line.strip().startswith("plugin:") for line in removed), removed
    expected = [
        line
        for (_, name), (plugin, planner) in test_bringup.PYTHON_PLUGINS.items()
        for line in (f'plugin: "{plugin}"', *_served(name, planner))
    ]
    assert sorted(line.strip() for line in added) == sorted(expected)
    # each at the indentation of the line it replaces
    replaced = '      plugin: "nav2_pyif_bridge::PyController"\n      key: "robot1/FollowPath"'
    assert replaced in edited


def test_the_native_plugins_and_the_stock_controllers_package() -> None:
    assert test_bringup.native_plugins(HUMBLE_SHAPED) == {
        ("controller_server", "progress_checker"): "nav2_controller::SimpleProgressChecker",
        ("controller_server", "FollowPath"): "dwb_core::DWBLocalPlanner",
        ("planner_server", "GridBased"): "nav2_navfn_planner/NavfnPlanner",
    }
    assert test_bringup._native_package(HUMBLE_SHAPED) == "dwb_core"
    assert test_bringup._native_package(LYRICAL_SHAPED) == "nav2_mppi_controller"


def test_params_without_one_of_the_plugins_are_refused() -> None:
    without_planner = HUMBLE_SHAPED.split("planner_server:")[0]
    with pytest.raises(AssertionError, match="the stock params changed"):
        test_bringup.python_params(without_planner, _served)


def test_the_tutorials_plugins_change_two_lines_only() -> None:
    edited = test_bringup.python_params(LYRICAL_SHAPED, _served, test_bringup.TUTORIAL_PLUGINS)
    assert "nav2_controller::SimpleProgressChecker" in edited
    assert edited.count("nav2_pyif_bridge::") == 2
