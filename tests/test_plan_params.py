"""Plan (NumPy first, reads like nav_msgs/Path) and Parameters (typed, declared, updated)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped
from nav2_pyif import Parameters, Plan
from nav2_pyif.params import declares
from nav_msgs.msg import Path

pytestmark = pytest.mark.unit


def test_plan_yaw_and_message_round_trip() -> None:
    xy_yaw = np.array([[0.0, 0.0, 0.0], [1.0, 0.5, math.pi / 2], [2.0, 1.0, -3.0]])
    plan = Plan(xy_yaw, "map", stamp_ns=5_000_000_123)
    assert np.allclose(plan.xy_yaw, xy_yaw)
    msg = plan.to_msg()
    assert isinstance(msg, Path) and all(isinstance(p, PoseStamped) for p in msg.poses)
    assert msg.header.stamp.sec == 5 and msg.header.stamp.nanosec == 123
    back = Plan.from_msg(msg)
    assert np.allclose(back.array, plan.array) and back.frame_id == "map"
    assert plan.length() == pytest.approx(2 * math.hypot(1.0, 0.5))


def test_plan_from_xy_faces_along_the_path_and_empty_plans_work() -> None:
    plan = Plan(np.array([[0.0, 0.0], [0.0, 1.0]]))
    assert plan.xy_yaw[:, 2] == pytest.approx([math.pi / 2, math.pi / 2])
    empty = Plan(np.zeros((0, 7)))
    assert len(empty) == 0 and empty.xy_yaw.shape == (0, 3) and empty.poses == []
    assert Plan.from_wire(empty.to_wire()).array.shape == (0, 7)


def test_parameters_declare_given_values_and_defaults() -> None:
    params = Parameters({"max_speed": 1, "name": "x"})
    assert params.declare("max_speed", 0.5) == 1.0  # int accepted for a float
    assert isinstance(params["max_speed"], float)
    assert params.declare("horizon", 30) == 30
    assert params.declared() == {"max_speed": 1.0, "horizon": 30}
    assert params["name"] == "x"  # given but not declared: still readable
    with pytest.raises(KeyError, match="neither given nor declared"):
        params["nope"]


def test_given_parameters_the_planner_neither_declares_nor_reads_are_reported() -> None:
    params = Parameters({"max_speed": 1.0, "max_sped": 2.0, "name": "x", "mode": "fast"})
    params.declare("max_speed", 0.5)
    assert params["name"] == "x" and "mode" in params  # read without declaring: used
    # what the planner declares is left out of each reason: a warning of several names
    # gives it once (declares)
    assert params.undeclared() == {
        "max_sped": "max_sped is not a parameter of this planner (did you mean max_speed?)"
    }
    assert Parameters({"k": 1, "j": 2}).undeclared() == {
        "k": "k is not a parameter of this planner",
        "j": "j is not a parameter of this planner",
    }
    assert declares(params.declared()) == "it declares: max_speed"
    assert declares(["b", "a"]) == "it declares: a, b" and declares([]) == "it declares: none"


def test_parameters_wrong_type_at_declare_raises() -> None:
    with pytest.raises(TypeError, match="use_x: expected bool, got int"):
        Parameters({"use_x": 1}).declare("use_x", True)
    with pytest.raises(TypeError, match="expected int, got float"):
        Parameters({"n": 1.5}).declare("n", 3)


def test_parameter_updates_reject_bad_types_and_keep_old_values() -> None:
    params = Parameters()
    params.declare("gain", 1.0)
    params.declare("weights", [1.0, 2.0])
    seen: list[dict[str, Any]] = []
    params.on_change(seen.append)
    applied, rejected = params.update({"gain": "fast", "weights": [3, 4], "gian": 2.0})
    assert rejected == {
        "gain": "gain: expected float, got str",
        # as in ROS 2: not one of the planner's parameters
        "gian": "gian is not a parameter of this planner (did you mean gain?); "
        "it declares: gain, weights",
    }
    assert applied == {"weights": [3.0, 4.0]}
    assert params["gain"] == 1.0 and params["weights"] == [3.0, 4.0]
    assert seen == [applied]


def test_fast_message_builders_match_the_generated_constructors() -> None:
    from geometry_msgs.msg import Twist, TwistStamped
    from nav2_pyif import _messages as messages

    assert messages.FAST_BUILDERS  # else every control cycle pays ~10 us more
    wire = {"frame_id": "odom", "stamp_ns": 5_000_000_007, "pose": [1, 2.0, 3, 0, 0, 0.6, 0.8]}
    fast = messages.pose_from_wire(wire)
    assert isinstance(fast, PoseStamped)
    assert fast == messages._slow_pose_stamped(wire)
    assert (fast.header.stamp.sec, fast.header.stamp.nanosec) == (5, 7)
    assert isinstance(fast.pose.position.x, float)
    fast.pose.position.x = 4.0  # setters still work on slot-built messages
    assert fast.pose.position.x == 4.0
    twist = messages.twist_stamped_from_wire(
        {"frame_id": "b", "stamp_ns": 1, "twist": [1.0, 0, 0, 0, 0, 2.0]}
    )
    assert isinstance(twist, TwistStamped) and isinstance(twist.twist, Twist)
    assert messages.twist_stamped_to_wire(twist)["twist"] == [1.0, 0, 0, 0, 0, 2.0]
