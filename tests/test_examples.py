"""The examples/ gallery, driven offline as README's "Bring your own planner" serves a user's
own module (``nav2-pyif sim --path examples ...``): each example through a real planner host
on both bundled maps, to the goal without a collision; OMPL's search ended by a cancel; the
MPC stepping by the controller server's period. Each needs its extra (``python -m pip install
'.[ompl]'`` in the clone, ``[casadi]``, ``[onnx]``), which scripts/bootstrap.sh installs;
without it its tests are skipped, saying which extra to install."""

from __future__ import annotations

import importlib.util
import logging
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif._context import PluginContext
from nav2_pyif.client import GlobalPlannerClient, Timeouts
from nav2_pyif.runner.inflation import inflate
from nav2_pyif.runner.mapfile import load_map
from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.run import pose_msg
from nav2_pyif.testing import assert_reaches_goal, drive

from tests.conftest import ROOT

pytestmark = pytest.mark.integration

EXAMPLES = ROOT / "examples"
MAPS = ["office", "cluttered"]
#: example -> (the import it needs, its extra)
NEEDS = {
    "ompl_planner": ("ompl", "ompl"),
    "casadi_mpc": ("casadi", "casadi"),
    "onnx_policy": ("onnxruntime", "onnx"),
    "dwa": ("numpy", "none: NumPy only"),
}


def needs(example: str) -> None:
    """Skip, naming the extra, when the example's library is not installed."""
    module, extra = NEEDS[example]
    if importlib.util.find_spec(module) is None:
        pytest.skip(
            f"examples/{example} needs {module}: python -m pip install '.[{extra}]' in the "
            "clone (scripts/bootstrap.sh installs it)"
        )


@pytest.fixture(scope="module")
def onnx_model(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The policy, written by the example's own script as its README says (never committed)."""
    needs("onnx_policy")
    model = tmp_path_factory.mktemp("onnx") / "policy.onnx"
    done = subprocess.run(
        [sys.executable, str(EXAMPLES / "onnx_policy" / "make_model.py"), str(model)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    return model


def run(map_name: str, **options: Any) -> Any:
    return drive(map=map_name, path=[str(EXAMPLES)], progress=False, **options)


@pytest.mark.timeout(300)
@pytest.mark.parametrize("map_name", MAPS)
@pytest.mark.parametrize("algorithm", ["rrtstar", "prmstar"])
def test_ompl_planner_plans_a_path_the_controller_drives(map_name: str, algorithm: str) -> None:
    needs("ompl_planner")
    result = run(
        map_name,
        controller="pure_pursuit",
        planner="ompl_planner.planner:OMPLPlanner",
        planner_params={"algorithm": algorithm},
        plans=3,  # PRM*'s threads once deadlocked the binding by the third plan
    )
    assert result.failed_plans == 0
    # the planner's default clearance (0.1 m beyond the footprint) less what pure pursuit's
    # corner cutting takes: without it OMPL's paths grazed obstacles and the robot stopped
    assert_reaches_goal(result, min_clearance=0.08)


@pytest.mark.timeout(300)
@pytest.mark.parametrize("map_name", MAPS)
@pytest.mark.parametrize(
    "controller", ["dwa.controller:DWA", "casadi_mpc.controller:MPC", "onnx_policy"]
)
def test_example_controller_reaches_the_goal(
    map_name: str, controller: str, request: pytest.FixtureRequest
) -> None:
    example = controller.split(".")[0]
    needs(example)
    params: dict[str, Any] = {}
    if example == "onnx_policy":
        controller = "onnx_policy.controller:OnnxPolicy"
        params["model"] = str(request.getfixturevalue("onnx_model"))
    assert_reaches_goal(run(map_name, controller=controller, controller_params=params))


@pytest.mark.parametrize("hz", [20.0, 10.0])
def test_the_mpc_steps_by_the_controller_servers_period(hz: float) -> None:
    """The MPC's model advances by controller_frequency's period per step: its first predicted
    pose is the first command applied for exactly one period."""
    needs("casadi_mpc")
    sys.path.insert(0, str(EXAMPLES))
    from casadi_mpc.controller import MPC

    costmap = inflate(load_map(map_path("office")), inscribed_radius=0.15, footprint=FOOTPRINT)
    mpc = MPC()
    mpc._attach(
        PluginContext(
            *("FollowPath", "controller_server", "map", "base_link", costmap),
            api.Parameters({}),
            logging.getLogger("test"),
            {"controller_frequency": hz},
        )
    )
    mpc.configure()
    mpc.set_plan(api.Plan(np.column_stack([np.linspace(2, 6, 81), np.full(81, 2.5)]), "map"))
    cmd = mpc.compute_velocity_commands(pose_msg(2.0, 2.5, 0.0), Twist(), None)
    first = mpc.problem.guess[0][:, 0]  # the predicted pose one step on
    assert cmd.twist.linear.x > 0.1
    assert first[0] - 2.0 == pytest.approx(cmd.twist.linear.x / hz, rel=1e-3)


def test_a_cancel_stops_ompl_mid_search(start_host: Any, zsession_factory: Any) -> None:
    """Nav2's cancel ends OMPL's solve through its termination condition: a 60 s budget is
    cut short within about a second of the cancel."""
    needs("ompl_planner")
    key = "nav2_pyif/test_robot/GridBased"
    host = start_host(
        "--key", key, "--planner", "ompl_planner.planner:OMPLPlanner", "--path", str(EXAMPLES)
    )
    costmap = inflate(load_map(map_path("office")), inscribed_radius=0.15, footprint=FOOTPRINT)
    client = GlobalPlannerClient(
        zsession_factory(host.endpoint),
        key,
        costmap,
        params={"max_time": 60.0},
        timeouts=Timeouts(call=2.0, lifecycle=5.0, configure=15.0, plan=90.0),
    )
    assert client.wait_for_host(15), host.log()
    client.configure()
    client.activate()
    cancel_at = time.monotonic() + 0.5
    with pytest.raises(api.PlannerCancelled, match="OMPL"):
        client.create_plan(
            pose(2.0, 2.5), pose(17.5, 12.0), cancel_checker=lambda: time.monotonic() > cancel_at
        )
    assert time.monotonic() - cancel_at < 2.0, host.log()  # not OMPL's 60 s


FOOTPRINT = [[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]


def pose(x: float, y: float) -> PoseStamped:
    msg = PoseStamped()
    msg.header.frame_id = "map"
    msg.pose.position.x, msg.pose.position.y = x, y
    msg.pose.orientation.w = 1.0
    return msg
