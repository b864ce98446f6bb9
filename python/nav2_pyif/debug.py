"""A controller's debug outputs: what Nav2's own controllers publish for RViz (local plan,
lookahead point, sampled trajectories), returned with the command and published by the plugin
on ``<plugin name>/<output name>`` while someone subscribes.

A planner declares them (``debug_outputs = {"trajectories": "visualization_msgs/msg/
MarkerArray"}``) and hands values to ``publish_debug`` during a cycle. Besides a message of the
declared type, these array forms are turned into messages here, in the costmap's global frame:

| declared type | array |
|---|---|
| visualization_msgs/msg/MarkerArray | (K, T, 2 or 3) trajectories: one LINE_STRIP each |
| nav_msgs/msg/Path | (N, 2) x, y or (N, 3) x, y, yaw |
| geometry_msgs/msg/PointStamped | (2,) or (3,) x, y[, z] |
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from nav2_pyif._ros_types import message_class, serialize, type_name_of


class DebugOutputError(ValueError):
    """A value for an undeclared output, or one that cannot become its declared type."""


def _header(msg: Any, frame_id: str, stamp: Any) -> None:
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp


def marker_array(trajectories: np.ndarray, frame_id: str, stamp: Any, ns: str) -> Any:
    from visualization_msgs.msg import Marker, MarkerArray

    clear = Marker(action=Marker.DELETEALL)  # K may shrink: drop the previous cycle's strips
    markers = [clear]
    xyz = np.zeros((*trajectories.shape[:2], 3))
    xyz[..., : trajectories.shape[2]] = trajectories
    for k, strip in enumerate(xyz):
        marker = Marker(ns=ns, id=k, type=Marker.LINE_STRIP, action=Marker.ADD)
        _header(marker, frame_id, stamp)
        marker.scale.x = 0.01
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = 0.1, 0.4, 1.0, 0.4
        marker.pose.orientation.w = 1.0
        marker.points = [_point(*p) for p in strip.tolist()]
        markers.append(marker)
    return MarkerArray(markers=markers)


def _point(x: float, y: float, z: float) -> Any:
    from geometry_msgs.msg import Point

    return Point(x=x, y=y, z=z)


def path(poses: np.ndarray, frame_id: str, stamp: Any) -> Any:
    from geometry_msgs.msg import PoseStamped
    from nav_msgs.msg import Path

    msg = Path()
    _header(msg, frame_id, stamp)
    for row in poses.tolist():
        pose = PoseStamped()
        _header(pose, frame_id, stamp)
        pose.pose.position.x, pose.pose.position.y = row[0], row[1]
        yaw = row[2] if len(row) > 2 else 0.0
        pose.pose.orientation.z, pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        msg.poses.append(pose)
    return msg


def point(xyz: np.ndarray, frame_id: str, stamp: Any) -> Any:
    from geometry_msgs.msg import PointStamped

    msg = PointStamped()
    _header(msg, frame_id, stamp)
    values = [float(v) for v in xyz] + [0.0] * (3 - len(xyz))
    msg.point = _point(*values)
    return msg


def to_message(name: str, type_name: str, value: Any, frame_id: str, stamp: Any) -> Any:
    """``value`` as a message of ``type_name``: as it is when it already is one, else from
    its array form (the table above)."""
    if not isinstance(value, np.ndarray) and not isinstance(value, (list, tuple)):
        if type_name_of(value) != type_name:
            raise DebugOutputError(
                f"debug output {name!r} is declared {type_name}, got {type_name_of(value)}"
            )
        return value
    array = np.asarray(value, dtype=np.float64)
    shapes = {
        "visualization_msgs/msg/MarkerArray": (3, (2, 3)),
        "nav_msgs/msg/Path": (2, (2, 3)),
        "geometry_msgs/msg/PointStamped": (1, (2, 3)),
    }
    if type_name not in shapes:
        raise DebugOutputError(
            f"debug output {name!r} ({type_name}) takes a message of that type, not an array"
        )
    ndim, lasts = shapes[type_name]
    if array.ndim != ndim or array.shape[-1] not in lasts or not np.isfinite(array).all():
        raise DebugOutputError(
            f"debug output {name!r} ({type_name}) takes a finite array of {ndim} dimensions "
            f"ending in 2 or 3, got shape {array.shape}"
        )
    if ndim == 3:
        return marker_array(array, frame_id, stamp, name)
    return path(array, frame_id, stamp) if ndim == 2 else point(array, frame_id, stamp)


def check_declared(declared: dict[str, str]) -> None:
    """Every declared type must be a message this host can build (at configure)."""
    for type_name in declared.values():
        message_class(type_name)


class DebugOutputs:
    """Per-session: which outputs are wanted this cycle, and what the planner published."""

    def __init__(self, declared: dict[str, str]) -> None:
        self.declared = dict(declared)
        self.wanted: frozenset[str] = frozenset()
        self._values: dict[str, Any] = {}

    def begin(self, wanted: Iterable[str]) -> None:
        self.wanted = frozenset(wanted) & self.declared.keys()
        self._values = {}

    def publish(self, name: str, value: Any) -> None:
        if name not in self.declared:
            declared = ", ".join(self.declared) or "none"
            raise DebugOutputError(
                f"debug output {name!r} is not declared (declared: {declared}); add it to the "
                "class's debug_outputs"
            )
        if name in self.wanted:
            self._values[name] = value

    def collect(self, frame_id: str, stamp: Any) -> list[dict[str, Any]]:
        """The wire DebugOutput maps of what was published and is wanted, serialized."""
        out = []
        for name, value in self._values.items():
            type_name = self.declared[name]
            msg = to_message(name, type_name, value, frame_id, stamp)
            out.append({"name": name, "type": type_name, "cdr": serialize(msg)})
        self._values = {}
        return out
