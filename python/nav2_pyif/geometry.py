"""Geometry a planner author needs and would otherwise copy: poses to (x, y, yaw), angles,
quaternions, paths as arrays, their length, the closest point and the carrot ahead on a path,
Nav2's speed limit.

Vectorised where it matters (NumPy arrays in, arrays out); shapes and units in each
docstring. ``nav2_pyif`` re-exports these names; the reference planners use them too. The
array forms of the quaternion conversions are the protocol's own (``quaternion_to_yaw``,
``yaw_to_quaternion``), re-exported here rather than copied.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from nav2_pyif_protocol.arrays import FloatArray, quaternion_to_yaw, yaw_to_quaternion

__all__ = [
    "carrot",
    "closest_index",
    "limit_speed",
    "path_length",
    "path_xy_yaw",
    "point_at_distance",
    "pose_xy_yaw",
    "quaternion_to_yaw",
    "remaining_length",
    "wrap",
    "yaw_of",
    "yaw_to_quaternion",
]


def yaw_of(orientation: Any) -> float:
    """A geometry_msgs Quaternion's yaw [rad], in (-pi, pi]. (The scalar form of
    ``quaternion_to_yaw``, which takes (..., 4) qx, qy, qz, qw arrays: ~20x faster on one.)"""
    q = orientation
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def pose_xy_yaw(pose: Any) -> tuple[float, float, float]:
    """x, y [m] and yaw [rad] of a geometry_msgs Pose or PoseStamped."""
    p = getattr(pose, "pose", pose)
    return float(p.position.x), float(p.position.y), yaw_of(p.orientation)


def wrap(angle: Any) -> Any:
    """Angles [rad] to (-pi, pi]; a scalar or an array of any shape."""
    return np.arctan2(np.sin(angle), np.cos(angle))


def path_xy_yaw(path: Any) -> FloatArray:
    """A nav_msgs Path (or a sequence of PoseStamped) -> (N, 3) float64: x, y [m], yaw [rad].
    A ``Plan`` already has this as ``plan.xy_yaw``."""
    poses = getattr(path, "poses", path)
    return np.array([pose_xy_yaw(p) for p in poses], dtype=np.float64).reshape(-1, 3)


def closest_index(
    path_xy: FloatArray, x: float, y: float, start: int = 0, window: int | None = None
) -> int:
    """Index of the point of ``path_xy`` ((N, 2+) [m]) closest to (x, y), searching from
    ``start`` (progress along the path is monotone) over ``window`` points (all when None)."""
    end = len(path_xy) if window is None else min(len(path_xy), start + window)
    if end <= start:
        return max(0, len(path_xy) - 1)
    d = np.hypot(path_xy[start:end, 0] - x, path_xy[start:end, 1] - y)
    return start + int(np.argmin(d))


def path_length(path_xy: Any) -> float:
    """Arc length [m] of a path: ``path_xy`` (N, 2+) x, y [m] (a ``Plan``'s ``xy`` or
    ``xy_yaw``); 0 for None or fewer than two points."""
    xy = np.zeros((0, 2)) if path_xy is None else np.asarray(path_xy, dtype=np.float64)
    if len(xy) < 2:
        return 0.0
    seg = np.diff(xy[:, :2], axis=0)
    return float(np.hypot(seg[:, 0], seg[:, 1]).sum())


def arc_lengths(path_xy: FloatArray) -> FloatArray:
    """(N,) arc length [m] along ``path_xy`` ((N, 2+)) from its first point to each (0 for the
    first; a repeated point adds nothing)."""
    out = np.zeros(len(path_xy))
    if len(path_xy) > 1:
        seg = np.diff(path_xy[:, :2], axis=0)
        np.cumsum(np.hypot(seg[:, 0], seg[:, 1]), out=out[1:])
    return out


def remaining_length(path_xy: FloatArray, index: int) -> float:
    """Arc length [m] of ``path_xy`` ((N, 2+)) from point ``index`` to its end."""
    return path_length(path_xy[index:])


def point_at_distance(path_xy: FloatArray, index: int, distance: float) -> FloatArray:
    """The (2,) point ``distance`` metres along ``path_xy`` ((N, 2+)) after point ``index``,
    interpolated between points; the last point when the path is shorter."""
    xy = path_xy[:, :2]
    seg = np.diff(xy[index:], axis=0)
    lengths = np.hypot(seg[:, 0], seg[:, 1])
    cumulative = np.cumsum(lengths)
    k = int(np.searchsorted(cumulative, distance))
    if k >= len(lengths):
        last: FloatArray = xy[-1].copy()
        return last
    before = cumulative[k] - lengths[k]
    t = (distance - before) / lengths[k] if lengths[k] > 0 else 0.0
    point: FloatArray = xy[index + k] + t * seg[k]
    return point


def carrot(
    path_xy: FloatArray, x: float, y: float, lookahead: float, start: int = 0
) -> tuple[FloatArray, int]:
    """Pure pursuit's carrot: the (2,) point ``lookahead`` metres along ``path_xy``
    ((N, 2+) [m]) past the point closest to the robot at (x, y) [m], and that closest
    index (pass it back as ``start`` next cycle, so that progress never goes backwards)."""
    index = closest_index(path_xy, x, y, start)
    return point_at_distance(path_xy, index, lookahead), index


def limit_speed(v_max: float, speed_limit: tuple[float, bool] | None) -> float:
    """Nav2's speed limit applied to ``v_max`` [m/s]: ``speed_limit`` is (value, percentage)
    as ``Controller.speed_limit`` holds it, absolute [m/s] or a percentage of the maximum."""
    if speed_limit is None:
        return v_max
    value, percentage = speed_limit
    return v_max * value / 100.0 if percentage else min(v_max, value)
