"""Wire dicts <-> real rclpy message objects (geometry_msgs, std_msgs, builtin_interfaces).

The control loop builds a PoseStamped, a Twist and a TwistStamped every cycle. The generated
constructors cost ~5 us each (kwargs, nested defaults, per-field setters), a large share of
the protocol's budget, so these builders fill the generated classes' slots directly. They
produce the same objects (checked at import against the constructors, falling back to them
if a rosidl version ever lays messages out differently).
"""

from __future__ import annotations

from typing import Any

from builtin_interfaces.msg import Time
from geometry_msgs.msg import Point, Pose, PoseStamped, Quaternion, Twist, TwistStamped, Vector3
from std_msgs.msg import Header

NS_PER_S = 1_000_000_000


def stamp_to_ns(stamp: Any) -> int:
    return int(stamp.sec) * NS_PER_S + int(stamp.nanosec)


def ns_to_stamp(ns: int) -> Any:
    sec, nanosec = divmod(int(ns), NS_PER_S)
    return Time(sec=sec, nanosec=nanosec)


# --- slot-level builders ------------------------------------------------------------------


def _blank(cls: Any) -> Any:
    """An instance without running __init__; fields are filled by the caller."""
    if "_check_fields" in cls.__slots__:  # Iron and later

        def make() -> Any:
            msg = cls.__new__(cls)
            msg._check_fields = False
            return msg

        return make
    return lambda: cls.__new__(cls)


_new_time, _new_header = _blank(Time), _blank(Header)
_new_point, _new_quat, _new_pose = _blank(Point), _blank(Quaternion), _blank(Pose)
_new_pose_stamped, _new_vector = _blank(PoseStamped), _blank(Vector3)
_new_twist, _new_twist_stamped = _blank(Twist), _blank(TwistStamped)


def _fast_header(frame_id: str, stamp_ns: int) -> Any:
    time, header = _new_time(), _new_header()
    time._sec, time._nanosec = divmod(stamp_ns, NS_PER_S)
    header._stamp, header._frame_id = time, frame_id
    return header


def _fast_twist(v: list[float]) -> Any:
    linear, angular, twist = _new_vector(), _new_vector(), _new_twist()
    linear._x, linear._y, linear._z = float(v[0]), float(v[1]), float(v[2])
    angular._x, angular._y, angular._z = float(v[3]), float(v[4]), float(v[5])
    twist._linear, twist._angular = linear, angular
    return twist


def _fast_pose_stamped(wire: dict[str, Any]) -> Any:
    x, y, z, qx, qy, qz, qw = wire["pose"]
    point, quat, pose, msg = _new_point(), _new_quat(), _new_pose(), _new_pose_stamped()
    point._x, point._y, point._z = float(x), float(y), float(z)
    quat._x, quat._y, quat._z, quat._w = float(qx), float(qy), float(qz), float(qw)
    pose._position, pose._orientation = point, quat
    msg._header, msg._pose = _fast_header(wire["frame_id"], wire["stamp_ns"]), pose
    return msg


def _fast_twist_stamped(wire: dict[str, Any]) -> Any:
    msg = _new_twist_stamped()
    msg._header = _fast_header(wire["frame_id"], wire["stamp_ns"])
    msg._twist = _fast_twist(wire["twist"])
    return msg


# --- constructor-based builders (the reference the fast ones must equal) ------------------


def _slow_pose_stamped(wire: dict[str, Any]) -> Any:
    msg = PoseStamped()
    msg.header.frame_id = wire["frame_id"]
    msg.header.stamp = ns_to_stamp(wire["stamp_ns"])
    x, y, z, qx, qy, qz, qw = (float(v) for v in wire["pose"])
    position, orientation = msg.pose.position, msg.pose.orientation
    position.x, position.y, position.z = x, y, z
    orientation.x, orientation.y, orientation.z, orientation.w = qx, qy, qz, qw
    return msg


def _slow_twist(values: list[float]) -> Any:
    msg = Twist()
    msg.linear.x, msg.linear.y, msg.linear.z = (float(v) for v in values[:3])
    msg.angular.x, msg.angular.y, msg.angular.z = (float(v) for v in values[3:])
    return msg


def _slow_twist_stamped(wire: dict[str, Any]) -> Any:
    msg = TwistStamped()
    msg.header.frame_id = wire["frame_id"]
    msg.header.stamp = ns_to_stamp(wire["stamp_ns"])
    msg.twist = _slow_twist(wire["twist"])
    return msg


def _fast_builders_agree() -> bool:
    pose = {"frame_id": "f", "stamp_ns": 3 * NS_PER_S + 7, "pose": [1.0, 2, 3, 4, 5, 6, 7]}
    twist: dict[str, Any] = {"frame_id": "g", "stamp_ns": 9, "twist": [1.0, 2, 3, 4, 5, 6]}
    try:
        return bool(
            _fast_pose_stamped(pose) == _slow_pose_stamped(pose)
            and _fast_twist_stamped(twist) == _slow_twist_stamped(twist)
            and _fast_twist(twist["twist"]) == _slow_twist(twist["twist"])
        )
    except Exception:
        return False


FAST_BUILDERS = _fast_builders_agree()

# --- public API -----------------------------------------------------------------------------


def pose_from_wire(wire: dict[str, Any]) -> Any:
    """{frame_id, stamp_ns, pose: [x, y, z, qx, qy, qz, qw]} -> geometry_msgs/PoseStamped."""
    return _fast_pose_stamped(wire) if FAST_BUILDERS else _slow_pose_stamped(wire)


def twist_from_list(values: list[float]) -> Any:
    """[vx, vy, vz, wx, wy, wz] -> geometry_msgs/Twist."""
    return _fast_twist(values) if FAST_BUILDERS else _slow_twist(values)


def twist_stamped_from_wire(wire: dict[str, Any]) -> Any:
    return _fast_twist_stamped(wire) if FAST_BUILDERS else _slow_twist_stamped(wire)


def pose_to_wire(msg: Any) -> dict[str, Any]:
    p, q = msg.pose.position, msg.pose.orientation
    return {
        "frame_id": msg.header.frame_id,
        "stamp_ns": stamp_to_ns(msg.header.stamp),
        "pose": [
            float(p.x),
            float(p.y),
            float(p.z),
            float(q.x),
            float(q.y),
            float(q.z),
            float(q.w),
        ],
    }


def twist_to_list(msg: Any) -> list[float]:
    """Twist -> 6 floats (ints a planner stored are converted: the wire is float64)."""
    lin, ang = msg.linear, msg.angular
    return [float(lin.x), float(lin.y), float(lin.z), float(ang.x), float(ang.y), float(ang.z)]


def twist_stamped_to_wire(msg: Any) -> dict[str, Any]:
    return {
        "frame_id": msg.header.frame_id,
        "stamp_ns": stamp_to_ns(msg.header.stamp),
        "twist": twist_to_list(msg.twist),
    }
