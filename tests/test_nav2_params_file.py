"""The runner reads a Nav2 params file as Nav2 does: what it takes from each section, and a
clear error naming the parameter that Nav2 would refuse."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.nav2_params import Nav2ParamsError, read_nav2_params, sim_config
from nav2_pyif.runner.run import SimError

pytestmark = pytest.mark.unit

PARAMS = {
    "controller_server": {
        "ros__parameters": {
            "controller_frequency": 10.0,
            "failure_tolerance": 1.5,
            "goal_checker_plugins": ["general_goal_checker"],
            "controller_plugins": ["FollowPath"],
            "general_goal_checker": {
                "plugin": "nav2_controller::SimpleGoalChecker",
                "xy_goal_tolerance": 0.4,
                "yaw_goal_tolerance": 0.6,
                "stateful": False,
            },
            "FollowPath": {
                "plugin": "nav2_pyif_bridge::PyController",
                "python_module": "sim_functions",
                "python_delegates": ["compute_velocity_commands=go_straight"],
                "timeout": 0.08,
                "wait_for_host": 20.0,
                "inputs": ["scan"],
                "scan": {"topic": "/scan", "type": "sensor_msgs/msg/LaserScan"},
                "desired_linear_vel": 0.3,
                "limits": {"max_vel": 0.5},
            },
        }
    },
    "planner_server": {
        "ros__parameters": {
            "planner_plugins": ["GridBased"],
            "GridBased": {
                "plugin": "nav2_pyif_bridge::PyGlobalPlanner",
                "python_planner": "nav2_pyif_planners.astar:AStar",
                "key": "nav2_pyif/robot1/GridBased",
                "plan_timeout": 12.0,
                "allow_unknown": True,
            },
        }
    },
}


def write(tmp_path: Path, data: object) -> Path:
    path = tmp_path / "nav2_params.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def test_the_runner_takes_what_nav2_reads_from_each_section(tmp_path: Path) -> None:
    options = read_nav2_params(write(tmp_path, PARAMS)).options
    assert options == {
        "rate": 10.0,
        "failure_tolerance": 1.5,
        "goal_checker": GoalTolerances(0.4, 0.6, 0.25, 0.25),
        "stateful_goal_check": False,
        "controller": "sim_functions",
        "delegates": {"controller": {"compute_velocity_commands": "go_straight"}},
        # the bridge's own parameters (timeout, wait_for_host, inputs and theirs) stay apart
        "controller_params": {"desired_linear_vel": 0.3, "limits.max_vel": 0.5},
        "call_timeout": 0.08,
        "planner": "nav2_pyif_planners.astar:AStar",
        "planner_params": {"allow_unknown": True},
        "plan_wait": 12.0,
    }


def test_what_the_caller_gives_wins_over_the_file(tmp_path: Path) -> None:
    config = sim_config(
        map_path("office"),
        write(tmp_path, PARAMS),
        rate=None,  # not given: the file's
        call_timeout=0.5,
        controller_params={"desired_linear_vel": 0.2},
        path=["here"],
    )
    assert config.rate == 10.0 and config.call_timeout == 0.5
    assert config.controller_params == {"desired_linear_vel": 0.2, "limits.max_vel": 0.5}
    assert config.params_file == tmp_path / "nav2_params.yaml"
    assert config.path == ["here"]


def test_a_file_that_is_not_a_plugin_of_ours_leaves_its_section_alone(tmp_path: Path) -> None:
    dwb = {"controller_server": {"ros__parameters": {"FollowPath": {"plugin": "dwb_core::X"}}}}
    assert read_nav2_params(write(tmp_path, dwb)).options == {}


@pytest.mark.parametrize(
    ("where", "value", "words"),
    [
        (("FollowPath", "timeout"), "fast", "controller_server.FollowPath.timeout: 'fast' is not"),
        (("controller_frequency",), -5, "controller_server.controller_frequency: -5 must be > 0"),
        (("FollowPath", "python_delegates"), ["compute=x"], "unknown delegate role 'compute'"),
    ],
)
def test_a_value_nav2_would_refuse_is_named(
    tmp_path: Path, where: tuple[str, ...], value: object, words: str
) -> None:
    data = yaml.safe_load(yaml.safe_dump(PARAMS))
    section = data["controller_server"]["ros__parameters"]
    for name in where[:-1]:
        section = section[name]
    section[where[-1]] = value
    path = write(tmp_path, data)
    with pytest.raises(Nav2ParamsError, match=words):
        read_nav2_params(path)
    with pytest.raises(SimError, match=f"{path}: .*{words}"):
        sim_config(map_path("office"), path)


def test_no_file_here_is_the_runner_defaults(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    assert sim_config(map_path("office")).params_file is None
    write(tmp_path, PARAMS)
    assert sim_config(map_path("office")).rate == 10.0  # ./nav2_params.yaml by default
    assert sim_config(map_path("office"), None).rate == 20.0
    with pytest.raises(SimError, match=r"cannot read Nav2 params file missing\.yaml"):
        sim_config(map_path("office"), "missing.yaml")
