"""Codec validation: malformed messages get clear, typed errors; canonical encoding."""

from __future__ import annotations

import math

import msgpack
import pytest
from nav2_pyif_protocol.codec import (
    ErrorInfo,
    ProtocolError,
    Reply,
    Request,
    decode_reply,
    decode_request,
    encode_reply,
    encode_request,
)
from nav2_pyif_protocol.constants import PROTOCOL_VERSION, ErrorType, Op
from nav2_pyif_protocol.keys import KeySpace

pytestmark = pytest.mark.unit

POSE = {"frame_id": "odom", "stamp_ns": 1, "pose": [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]}
COSTMAP = {
    "version": 1,
    "frame_id": "odom",
    "size_x": 4,
    "size_y": 3,
    "resolution": 0.05,
    "origin_x": 0.0,
    "origin_y": 0.0,
    "data": bytes(12),
    "footprint": b"",
    "robot_radius": 0.2,
}


def raw(**overrides: object) -> bytes:
    message = {
        "v": PROTOCOL_VERSION,
        "op": "compute_velocity_commands",
        "sid": "s",
        "epoch": 1,
        "seq": 3,
        "body": {"pose": POSE, "velocity": [0.0] * 6},
    }
    message.update(overrides)
    return msgpack.packb(message, use_bin_type=True)


def bad_request(data: bytes) -> ProtocolError:
    with pytest.raises(ProtocolError) as info:
        decode_request(data)
    return info.value


def test_a_valid_request_decodes() -> None:
    request = decode_request(raw())
    assert request.op is Op.COMPUTE_VELOCITY_COMMANDS and request.seq == 3
    assert request.body["velocity"] == [0.0] * 6


def test_version_mismatch_names_both_versions() -> None:
    error = bad_request(raw(v=PROTOCOL_VERSION + 1))
    assert error.error_type is ErrorType.VERSION_MISMATCH
    assert str(PROTOCOL_VERSION + 1) in str(error) and str(PROTOCOL_VERSION) in str(error)


@pytest.mark.parametrize(
    ("data", "words"),
    [
        (b"\xc1not msgpack", "not valid msgpack"),
        (msgpack.packb([1, 2]), "not a msgpack map"),
        (raw(op="fly"), "unknown op 'fly'"),
        (raw(sid=5), "request.sid: expected str"),
        (raw(epoch=0), "request.epoch: expected an int >= 1, got 0"),
        (raw(body={"velocity": [0.0] * 6}), "missing field 'pose'"),
        (raw(body={"pose": POSE, "velocity": [0.0] * 5}), "array of 6 floats"),
        (
            raw(body={"pose": dict(POSE, pose=[0.0] * 7, frame_id=3), "velocity": [0.0] * 6}),
            "pose.frame_id: expected str",
        ),
        (
            raw(op="set_speed_limit", body={"speed_limit": 1.0, "percentage": 1}),
            "percentage: expected bool",
        ),
        (raw(op="set_parameters", body={"params": {"p": [1, "a"]}}), "array mixes"),
        (raw(op="set_parameters", body={"params": {"p": {"nested": 1}}}), "is not bool/int"),
        # the schema's int ranges, packed rows and cell counts, checked as the C++ codec does
        (raw(seq=-1), "request.seq: expected an int >= 0, got -1"),
        (raw(op="cancel_plan", body={"target_seq": -3}), "target_seq: expected an int >= 0"),
        (
            raw(op="set_plan", body={"path": {"frame_id": "m", "stamp_ns": 0, "poses": b"x" * 57}}),
            "set_plan request body.path.poses: 57 bytes is not a whole number of rows of 7",
        ),
        (
            raw(body={"pose": POSE, "velocity": [0.0] * 6, "costmap": COSTMAP | {"size_x": 2**32}}),
            "body.costmap.size_x: int 4294967296 is out of the uint32 range",
        ),
        (
            raw(body={"pose": POSE, "velocity": [0.0] * 6, "costmap": COSTMAP | {"size_x": 5}}),
            "body.costmap.data: 12 bytes, but size 5 x 3 needs 15",
        ),
        (
            raw(
                body={"pose": POSE, "velocity": [0.0] * 6, "costmap": COSTMAP | {"footprint": b"?"}}
            ),
            "body.costmap.footprint: 1 bytes is not a whole number of rows of 2 float64",
        ),
    ],
)
def test_malformed_requests_are_bad_requests_saying_why(data: bytes, words: str) -> None:
    error = bad_request(data)
    assert error.error_type is ErrorType.BAD_REQUEST
    assert words in str(error)


def test_encoding_is_canonical_whatever_the_dict_order() -> None:
    body_a = {"speed_limit": 2, "percentage": False}
    body_b = {"percentage": False, "speed_limit": 2.0}
    a = encode_request(Request(Op.SET_SPEED_LIMIT, "s", 1, 1, body_a))
    b = encode_request(Request(Op.SET_SPEED_LIMIT, "s", 1, 1, body_b))
    assert a == b
    # ints given for float fields travel as float64
    assert decode_request(a).body["speed_limit"] == 2.0
    assert isinstance(decode_request(a).body["speed_limit"], float)


def test_unknown_fields_are_ignored_for_forward_compatibility() -> None:
    request = decode_request(
        raw(extra="future", body={"pose": POSE, "velocity": [0.0] * 6, "new_field": 1})
    )
    assert request.body["velocity"] == [0.0] * 6  # unknown keys neither fail nor interfere
    reencoded = decode_request(encode_request(request))
    assert "new_field" not in reencoded.body  # and are not forwarded by a canonical encode


def test_non_finite_floats_survive() -> None:
    data = encode_request(
        Request(
            Op.COMPUTE_VELOCITY_COMMANDS,
            "s",
            1,
            1,
            {"pose": POSE, "velocity": [math.nan, math.inf, -0.0, 0, 0, 0]},
        )
    )
    velocity = decode_request(data).body["velocity"]
    assert math.isnan(velocity[0]) and velocity[1] == math.inf
    assert math.copysign(1.0, velocity[2]) == -1.0


def test_error_replies_round_trip() -> None:
    reply = Reply(4, False, "h", error=ErrorInfo("NoValidControl", "why", "tb", "x.Y"))
    decoded = decode_reply(
        encode_reply(reply, Op.COMPUTE_VELOCITY_COMMANDS), Op.COMPUTE_VELOCITY_COMMANDS
    )
    assert decoded == reply


def test_ok_reply_body_is_validated_against_its_op() -> None:
    data = encode_reply(Reply(1, True, "h", body={"cancelled": True}), Op.CANCEL)
    with pytest.raises(ProtocolError, match="missing field 'cmd_vel'"):
        decode_reply(data, Op.COMPUTE_VELOCITY_COMMANDS)


def test_keys() -> None:
    keys = KeySpace("nav2_pyif/robot1/FollowPath")
    assert keys.call(Op.SET_PLAN) == "nav2_pyif/robot1/FollowPath/rpc/set_plan"
    assert keys.call(Op.CANCEL_PLAN) == "nav2_pyif/robot1/FollowPath/cancel"
    assert keys.host_token("h1") == "nav2_pyif/robot1/FollowPath/host/h1"
    for bad in ["", "/a", "a/", "a//b", "a/*/b", "a/$b", "0/chatter", "42/a/b", "@ros2_lv/0"]:
        with pytest.raises(ValueError):
            KeySpace(bad)
    KeySpace("robot7/0/FollowPath")  # a number after the first chunk is no rmw_zenoh key


def test_prefixes_that_could_meet_rmw_zenoh_keys_are_refused_saying_why() -> None:
    with pytest.raises(ValueError, match="ROS domain id"):
        KeySpace("0/chatter")
    with pytest.raises(ValueError, match="rmw_zenoh"):
        KeySpace("robot/@ros2_lv")


def test_the_hot_path_fast_encoding_gives_the_canonical_bytes() -> None:
    from geometry_msgs.msg import PoseStamped, Twist
    from nav2_pyif._messages import pose_to_wire, twist_to_list
    from nav2_pyif.goal_tolerances import GoalTolerances

    from tests.conftest import make_costmap

    body = {
        "pose": pose_to_wire(PoseStamped()),
        "velocity": twist_to_list(Twist()),
        "goal_checker": GoalTolerances(0.1, 0.2, 0.3, 0.4).to_wire(),
        "costmap": make_costmap().to_wire(),
    }
    request = Request(Op.COMPUTE_VELOCITY_COMMANDS, "s", 1, 1, body)
    assert encode_request(request, validate=False) == encode_request(request)
    reply = Reply(
        1, True, "h", body={"cmd_vel": {"frame_id": "b", "stamp_ns": 0, "twist": [0.0] * 6}}
    )
    op = Op.COMPUTE_VELOCITY_COMMANDS
    assert encode_reply(reply, op, validate=False) == encode_reply(reply, op)


@pytest.mark.parametrize("version", [True, 1.0, "1", None])
def test_a_version_that_only_looks_like_1_is_a_mismatch(version: object) -> None:
    assert bad_request(raw(v=version)).error_type is ErrorType.VERSION_MISMATCH
