"""What a planner is told beyond its own parameters: the control period and the
inflation layer's parameters travel in configure's ``nav2_params``, reach the class style as
``Controller.control_period``, ``PlannerPlugin.nav2_params`` and ``Costmap.inflation`` (and
``circumscribed_cost()`` without an argument), and the function style as keyword arguments
(goal_checker, plan, control_period, cancel_checker) — through the host's real runtime and
codec, without Zenoh."""

from __future__ import annotations

import math
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from nav2_pyif import Costmap, Inflation
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.delegates import delegate_class
from nav2_pyif.server.loader import load_class
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif_protocol.arrays import pack_poses
from nav2_pyif_protocol.codec import Request, decode_request, encode_request
from nav2_pyif_protocol.constants import Op

from tests.conftest import configure_body, make_costmap
from tests.test_runtime import POSE, Driver

pytestmark = pytest.mark.unit

RECTANGLE = [[0.3, 0.15], [0.3, -0.15], [-0.3, -0.15], [-0.3, 0.15]]
NAV2 = {"controller_frequency": 20.0, "inflation_radius": 0.55, "cost_scaling_factor": 3.0}
TOLERANCES = {
    "xy_goal_tolerance": 0.25,
    "yaw_goal_tolerance": 0.25,
    "trans_stopped_velocity": 0.25,
    "rot_stopped_velocity": 0.25,
}


class Told(api.Controller):
    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        raise NotImplementedError


def configure(driver: Driver, nav2_params: dict[str, Any] | None) -> None:
    body = configure_body(
        driver.plugin_type,
        costmap=Costmap(make_costmap().data, 0.05, footprint=RECTANGLE).to_wire(),
    )
    if nav2_params is not None:
        body["nav2_params"] = nav2_params
    assert driver.call(Op.CONFIGURE, body).ok


def test_nav2_params_survive_the_codec() -> None:
    body = configure_body(nav2_params=NAV2)
    decoded = decode_request(encode_request(Request(Op.CONFIGURE, "s", 1, 1, body)))
    assert decoded.body["nav2_params"] == NAV2


def test_the_class_style_reads_the_control_period_and_the_inflation() -> None:
    runtime = PlannerRuntime(Told, "test-host")
    configure(Driver(runtime), NAV2)
    (session,) = runtime.sessions.values()
    planner = session.planner
    assert isinstance(planner, Told)
    assert planner.control_period == pytest.approx(0.05)
    assert planner.nav2_params == NAV2
    assert planner.costmap.inflation == Inflation(0.55, 3.0)
    # 252 * exp(-3 * (circumscribed - inscribed)) for the 0.6 x 0.3 m rectangle
    expected = int(252 * math.exp(-3.0 * (math.hypot(0.3, 0.15) - 0.15)))
    assert planner.costmap.circumscribed_cost() == expected
    # a later costmap keeps the inflation configure told
    Driver(runtime).call(
        Op.COMPUTE_VELOCITY_COMMANDS,
        {"pose": POSE, "velocity": [0.0] * 6, "costmap": make_costmap(version=9).to_wire()},
    )
    assert planner.costmap.version == 9 and planner.costmap.inflation == Inflation(0.55, 3.0)


def test_without_nav2_params_nothing_is_made_up() -> None:
    runtime = PlannerRuntime(Told, "test-host")
    configure(Driver(runtime), None)
    (session,) = runtime.sessions.values()
    planner = session.planner
    assert isinstance(planner, Told)
    assert planner.control_period is None and planner.nav2_params == {}
    with pytest.raises(ValueError, match="cost_scaling_factor is not known here"):
        planner.costmap.circumscribed_cost()
    assert planner.costmap.circumscribed_cost(3.0) > 0


def test_functions_get_the_keyword_arguments_they_name() -> None:
    cls = load_class("tests.fixtures.keyword_delegates:steer", kind="compute_velocity_commands")
    assert issubclass(cls, api.Controller)
    driver = Driver(PlannerRuntime(cls, "test-host"))
    configure(driver, NAV2)
    path = {"frame_id": "odom", "stamp_ns": 0, "poses": pack_poses(np.zeros((4, 7)))}
    assert driver.call(Op.SET_PLAN, {"path": path}).ok
    reply = driver.call(
        Op.COMPUTE_VELOCITY_COMMANDS,
        {"pose": POSE, "velocity": [0.0] * 6, "goal_checker": TOLERANCES},
    )
    assert reply.ok and reply.body is not None, reply.error
    linear_x, linear_y, linear_z, *_, angular_z = reply.body["cmd_vel"]["twist"]
    assert (linear_x, linear_y, linear_z) == (4.0, 0.25, pytest.approx(0.05))
    assert angular_z > 0  # circumscribed_cost() from the inflation configure told


def test_a_planner_function_gets_the_cancel_checker() -> None:
    cls = load_class("tests.fixtures.keyword_delegates:plan", kind="create_plan")
    assert issubclass(cls, api.GlobalPlanner)
    driver = Driver(PlannerRuntime(cls, "test-host"), "global_planner")
    configure(driver, None)
    reply = driver.call(Op.CREATE_PLAN, {"start": POSE, "goal": POSE})
    assert reply.ok and reply.body is not None, reply.error
    assert len(reply.body["path"]["poses"]) == 2 * 56  # cancel_checker() said False


def test_a_function_without_a_known_role_is_refused_saying_how() -> None:
    with pytest.raises(PlannerLoadError, match="is a function, but which role it plays"):
        load_class("tests.fixtures.keyword_delegates:steer")
    # a module named alone, served as a planner, must have create_plan
    with pytest.raises(PlannerLoadError, match="defines no function create_plan"):
        delegate_class("tests.fixtures.seed_delegates", {}, kind="create_plan")
