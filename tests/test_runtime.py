"""The host's dispatch core, in process: every error path becomes a typed reply, logged once,
and the next call works."""

from __future__ import annotations

import gc
import logging
import math
from typing import Any

import msgpack
import nav2_pyif as api
import pytest
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.roles import parse_delegates
from nav2_pyif.server.delegates import delegate_class
from nav2_pyif.server.loader import load_class
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif_protocol.arrays import pack_poses
from nav2_pyif_protocol.codec import Reply, Request, decode_reply, encode_request
from nav2_pyif_protocol.constants import PROTOCOL_VERSION, Op

from tests.conftest import CONTROLLER_ERRORS, configure_body
from tests.fixtures.echo_planners import FaultyController, LinePlanner

pytestmark = pytest.mark.unit

POSE = {"frame_id": "odom", "stamp_ns": 7, "pose": [1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]}


class Driver:
    """Plays the plugin's part against a runtime, without Zenoh."""

    def __init__(self, runtime: PlannerRuntime, plugin_type: str = "controller") -> None:
        self.runtime = runtime
        self.plugin_type = plugin_type
        self.seq = 0
        self.epoch = 1

    def call(self, op: Op, body: dict[str, Any] | None = None, sid: str = "s1") -> Reply:
        self.seq += 1
        request = Request(op, sid, self.epoch, self.seq, body or {})
        return decode_reply(self.runtime.handle(encode_request(request)), op)

    def configure(self, params: dict[str, Any] | None = None) -> Reply:
        return self.call(Op.CONFIGURE, configure_body(self.plugin_type, params=params or {}))

    def cycle(self) -> Reply:
        return self.call(Op.COMPUTE_VELOCITY_COMMANDS, {"pose": POSE, "velocity": [0.0] * 6})


@pytest.fixture
def driver() -> Driver:
    d = Driver(PlannerRuntime(FaultyController, "test-host"))
    assert d.configure().ok
    return d


def set_fault(driver: Driver, fault: str) -> None:
    reply = driver.call(Op.SET_PARAMETERS, {"params": {"fault": fault}})
    assert reply.ok and reply.body == {"rejected": {}}


def test_configure_reports_declared_parameters(driver: Driver) -> None:
    reply = driver.configure({"gain": 3})
    assert reply.ok and reply.body is not None
    assert reply.body["declared"] == {"gain": 3.0, "label": "echo", "fault": "none", "sleep_s": 0.0}


def test_a_cycle_returns_the_planners_twist(driver: Driver) -> None:
    reply = driver.cycle()
    assert reply.ok and reply.body is not None
    cmd = reply.body["cmd_vel"]
    assert cmd["frame_id"] == "base_link" and cmd["twist"][3] == 1.0  # costmap version
    assert reply.compute_ns > 0 and reply.host == "test-host"


CONTROLLER_NAMED = [*CONTROLLER_ERRORS, "PlannerException"]  # Humble-style too


@pytest.mark.parametrize("name", CONTROLLER_NAMED)
def test_nav2_named_exceptions_keep_their_type(
    driver: Driver, name: str, caplog: pytest.LogCaptureFixture
) -> None:
    set_fault(driver, name)
    with caplog.at_level(logging.ERROR, logger="nav2_pyif.server.host"):
        reply = driver.cycle()
    assert not reply.ok and reply.error is not None
    assert reply.error.type == name
    assert f"{name} raised on purpose" in reply.error.message
    assert "compute_velocity_commands" in reply.error.traceback
    # the planner's own frames first: none of the host's call path into it
    frames = [line for line in reply.error.traceback.splitlines() if line.startswith("  File")]
    assert "echo_planners.py" in frames[0] and "runtime.py" not in reply.error.traceback
    assert reply.error.python_type == f"nav2_pyif.exceptions.{name}"
    assert len([r for r in caplog.records if name in r.getMessage()]) == 1  # logged once
    set_fault(driver, "none")
    assert driver.cycle().ok  # the next call works


@pytest.mark.parametrize(
    ("fault", "error_type", "words"),
    [
        ("zero_division", "ControllerException", "ZeroDivisionError: division by zero"),
        (
            "none_return",
            "ControllerException",
            "returned NoneType; expected geometry_msgs.msg.TwistStamped",
        ),
        ("twist_return", "ControllerException", "wrap it: TwistStamped"),
        ("nan", "NoValidControl", "non-finite velocity: linear.x=nan, angular.z=inf"),
        ("sys_exit", "ControllerException", "SystemExit: 3"),
        ("keyboard_interrupt", "ControllerException", "KeyboardInterrupt"),
        ("recursion", "ControllerException", "RecursionError"),
    ],
)
def test_misbehaviour_becomes_a_typed_error_naming_it(
    driver: Driver, fault: str, error_type: str, words: str
) -> None:
    set_fault(driver, fault)
    reply = driver.cycle()
    assert not reply.ok and reply.error is not None
    assert reply.error.type == error_type
    assert words in reply.error.message
    set_fault(driver, "none")
    assert driver.cycle().ok


def test_recursion_tracebacks_are_bounded(driver: Driver) -> None:
    set_fault(driver, "recursion")
    reply = driver.cycle()
    assert reply.error is not None and len(reply.error.traceback) < 20_000


def test_unknown_session_and_stale_epoch_say_so(driver: Driver) -> None:
    reply = driver.call(Op.ACTIVATE, sid="never-configured")
    assert reply.error is not None and reply.error.type == "SessionUnknown"
    driver.epoch = 2
    reply = driver.cycle()
    assert reply.error is not None and reply.error.type == "SessionUnknown"


def test_protocol_errors(driver: Driver) -> None:
    garbage = decode_reply(driver.runtime.handle(b"\x93\x01\x02"), Op.ACTIVATE)
    assert garbage.error is not None and garbage.error.type == "BadRequest"
    future = msgpack.packb({"v": PROTOCOL_VERSION + 1, "op": "activate", "seq": 41})
    mismatch = decode_reply(driver.runtime.handle(future), Op.ACTIVATE)
    assert mismatch.error is not None and mismatch.error.type == "VersionMismatch"
    assert mismatch.seq == 41
    wrong_key = Request(Op.ACTIVATE, "s1", 1, 99, {})
    reply = decode_reply(
        driver.runtime.handle(encode_request(wrong_key), key_op="reset"), Op.ACTIVATE
    )
    assert reply.error is not None and "sent to key of op 'reset'" in reply.error.message
    plan_op = driver.call(Op.CREATE_PLAN, {"start": POSE, "goal": POSE})
    assert plan_op.error is not None and "not an operation of a controller" in plan_op.error.message


def test_configure_failures_are_invalid_controller() -> None:
    d = Driver(PlannerRuntime(FaultyController, "h"))
    reply = d.configure({"fail_configure": True})
    assert reply.error is not None and reply.error.type == "InvalidController"
    assert "configure refused on purpose" in reply.error.message
    wrong_type = d.configure({"gain": "fast"})
    assert (
        wrong_type.error is not None and "gain: expected float, got str" in wrong_type.error.message
    )
    planner_for_controller = Driver(PlannerRuntime(FaultyController, "h"), "global_planner")
    reply = planner_for_controller.configure()
    assert reply.error is not None and reply.error.type == "InvalidPlanner"
    assert "serves" in reply.error.message


def test_non_finite_plans_are_refused(driver: Driver) -> None:
    poses = pack_poses([[math.nan, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]])
    reply = driver.call(Op.SET_PLAN, {"path": {"frame_id": "odom", "stamp_ns": 0, "poses": poses}})
    assert reply.error is not None and reply.error.type == "InvalidPath"


@pytest.mark.parametrize(
    ("mode", "error_type"),
    [
        ("occupied", "GoalOccupied"),
        ("nan", "NoValidPathCouldBeFound"),
        ("wrong_type", "PlannerException"),
    ],
)
def test_planner_errors(mode: str, error_type: str) -> None:
    d = Driver(PlannerRuntime(LinePlanner, "h"), "global_planner")
    assert d.configure({"mode": mode}).ok
    reply = d.call(Op.CREATE_PLAN, {"start": POSE, "goal": POSE})
    assert reply.error is not None and reply.error.type == error_type
    assert d.call(Op.SET_PARAMETERS, {"params": {"mode": "msg"}}).ok
    ok = d.call(Op.CREATE_PLAN, {"start": POSE, "goal": POSE})
    assert ok.ok and ok.body is not None and len(ok.body["path"]["poses"]) == 11 * 56


def test_loader_errors_are_clear() -> None:
    with pytest.raises(PlannerLoadError, match="not of the form"):
        load_class("no_colon")
    with pytest.raises(PlannerLoadError, match="No module named 'no_such_module'"):
        load_class("no_such_module:X")
    with pytest.raises(PlannerLoadError, match="fails at import on purpose"):
        load_class("tests.fixtures.broken_at_import:X")
    with pytest.raises(PlannerLoadError, match="has no class 'Nope'; planners it defines: Echo"):
        load_class("tests.fixtures.echo_planners:Nope")
    with pytest.raises(PlannerLoadError, match="not a nav2_pyif Controller"):
        load_class("nav2_pyif:__version__")
    with pytest.raises(PlannerLoadError, match="is a function, but which role it plays"):
        load_class("tests.fixtures.echo_planners:is_path_msg")
    with pytest.raises(PlannerLoadError, match="does not implement compute_velocity_commands"):
        load_class("nav2_pyif:Controller")
    assert load_class("tests.fixtures.echo_planners:LinePlanner") is LinePlanner


def test_delegate_items_as_the_nav2_plugin_passes_them() -> None:
    """The plugin hands its python_delegates items to planner-host as they are: comma lists,
    bare roles (the function of that name), the last of a role given twice."""
    assert parse_delegates(["set_plan=a, reset = b", "compute_velocity_commands", "reset=c"]) == {
        "set_plan": "a",
        "reset": "c",
        "compute_velocity_commands": "compute_velocity_commands",
    }
    assert parse_delegates(["", " , "]) == {}
    with pytest.raises(PlannerLoadError, match="not of the form role=function"):
        parse_delegates(["set_plan="])


def test_delegates_build_a_controller() -> None:
    roles = parse_delegates(
        ["compute_velocity_commands=compute,set_plan=on_plan", "set_speed_limit=on_limit"]
    )
    cls = delegate_class("tests.fixtures.seed_delegates", roles)
    assert issubclass(cls, api.Controller)
    with pytest.raises(PlannerLoadError, match="no function 'missing'"):
        delegate_class("tests.fixtures.seed_delegates", {"compute_velocity_commands": "missing"})
    with pytest.raises(PlannerLoadError, match="exactly one of"):
        delegate_class("tests.fixtures.seed_delegates", {"set_plan": "on_plan"})
    with pytest.raises(PlannerLoadError, match="unknown delegate role"):
        delegate_class("tests.fixtures.seed_delegates", {"fly": "on_plan"})


def test_a_controllers_configure_warms_the_message_serialization(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Its first cycle with an input must not load rclpy's serialization (tests/
    test_inputs_debug.py checks what the warm-up loads); other plugin types need none."""
    warmed: list[bool] = []
    monkeypatch.setattr("nav2_pyif.server.runtime.warm_serialization", lambda: warmed.append(True))
    assert Driver(PlannerRuntime(FaultyController, "test-host")).configure().ok
    assert warmed == [True]
    planner = Driver(PlannerRuntime(LinePlanner, "test-host"), plugin_type="global_planner")
    assert planner.configure().ok
    assert warmed == [True]


def test_a_configured_session_is_out_of_the_full_collections_sight(driver: Driver) -> None:
    """A full collection over what a configure built (a JAX planner: 100 000 objects) would
    stall every robot's cycle for a control period: configure freezes what it leaves."""
    gc.unfreeze()
    assert driver.configure().ok
    planner = driver.runtime.sessions["s1"].planner
    assert gc.get_freeze_count() > 0
    assert not any(tracked is planner for tracked in gc.get_objects())
