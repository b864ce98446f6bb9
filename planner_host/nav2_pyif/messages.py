"""Wire dicts <-> real rclpy message objects (geometry_msgs, std_msgs, builtin_interfaces)."""

from __future__ import annotations

from typing import Any

from builtin_interfaces.msg import Time
from geometry_msgs.msg import PoseStamped, Twist, TwistStamped

NS_PER_S = 1_000_000_000


def stamp_to_ns(stamp: Any) -> int:
    return int(stamp.sec) * NS_PER_S + int(stamp.nanosec)


def ns_to_stamp(ns: int) -> Any:
    sec, nanosec = divmod(int(ns), NS_PER_S)
    return Time(sec=sec, nanosec=nanosec)


def pose_from_wire(wire: dict[str, Any]) -> Any:
    """{frame_id, stamp_ns, pose: [x, y, z, qx, qy, qz, qw]} -> geometry_msgs/PoseStamped."""
    msg = PoseStamped()
    msg.header.frame_id = wire["frame_id"]
    msg.header.stamp = ns_to_stamp(wire["stamp_ns"])
    x, y, z, qx, qy, qz, qw = wire["pose"]
    position, orientation = msg.pose.position, msg.pose.orientation
    position.x, position.y, position.z = x, y, z
    orientation.x, orientation.y, orientation.z, orientation.w = qx, qy, qz, qw
    return msg


def pose_to_wire(msg: Any) -> dict[str, Any]:
    p, q = msg.pose.position, msg.pose.orientation
    return {
        "frame_id": msg.header.frame_id,
        "stamp_ns": stamp_to_ns(msg.header.stamp),
        "pose": [p.x, p.y, p.z, q.x, q.y, q.z, q.w],
    }


def twist_from_list(values: list[float]) -> Any:
    """[vx, vy, vz, wx, wy, wz] -> geometry_msgs/Twist."""
    msg = Twist()
    msg.linear.x, msg.linear.y, msg.linear.z = values[0], values[1], values[2]
    msg.angular.x, msg.angular.y, msg.angular.z = values[3], values[4], values[5]
    return msg


def twist_to_list(msg: Any) -> list[float]:
    lin, ang = msg.linear, msg.angular
    return [lin.x, lin.y, lin.z, ang.x, ang.y, ang.z]


def twist_stamped_from_wire(wire: dict[str, Any]) -> Any:
    msg = TwistStamped()
    msg.header.frame_id = wire["frame_id"]
    msg.header.stamp = ns_to_stamp(wire["stamp_ns"])
    msg.twist = twist_from_list(wire["twist"])
    return msg


def twist_stamped_to_wire(msg: Any) -> dict[str, Any]:
    return {
        "frame_id": msg.header.frame_id,
        "stamp_ns": stamp_to_ns(msg.header.stamp),
        "twist": twist_to_list(msg.twist),
    }
