"""Small vectorised helpers shared by the reference controllers."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


def pose_xy_yaw(pose: Any) -> tuple[float, float, float]:
    """geometry_msgs/PoseStamped -> (x, y, yaw)."""
    p, q = pose.pose.position, pose.pose.orientation
    yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    return p.x, p.y, yaw


def wrap(angle: Any) -> Any:
    """Angles to (-pi, pi]; scalars or arrays."""
    return np.arctan2(np.sin(angle), np.cos(angle))


def closest_index(
    path_xy: FloatArray, x: float, y: float, start: int = 0, window: int | None = None
) -> int:
    """Index of the path point closest to (x, y), searching from ``start`` (monotone progress)
    over ``window`` points (all when None)."""
    end = len(path_xy) if window is None else min(len(path_xy), start + window)
    if end <= start:
        return max(0, len(path_xy) - 1)
    d = np.hypot(path_xy[start:end, 0] - x, path_xy[start:end, 1] - y)
    return start + int(np.argmin(d))


def remaining_length(path_xy: FloatArray, index: int) -> float:
    """Arc length from path point ``index`` to the end [m]."""
    seg = np.diff(path_xy[index:], axis=0)
    return float(np.hypot(seg[:, 0], seg[:, 1]).sum()) if len(seg) else 0.0


def point_at_distance(path_xy: FloatArray, index: int, distance: float) -> FloatArray:
    """The point ``distance`` metres along the path after point ``index`` (interpolated),
    or the last point."""
    seg = np.diff(path_xy[index:], axis=0)
    lengths = np.hypot(seg[:, 0], seg[:, 1])
    cumulative = np.cumsum(lengths)
    k = int(np.searchsorted(cumulative, distance))
    if k >= len(lengths):
        last: FloatArray = path_xy[-1].copy()
        return last
    before = cumulative[k] - lengths[k]
    t = (distance - before) / lengths[k] if lengths[k] > 0 else 0.0
    point: FloatArray = path_xy[index + k] + t * seg[k]
    return point


def limit_speed(v_max: float, speed_limit: tuple[float, bool] | None) -> float:
    """Apply Nav2's speed limit: absolute [m/s] or percentage of the maximum."""
    if speed_limit is None:
        return v_max
    value, percentage = speed_limit
    return v_max * value / 100.0 if percentage else min(v_max, value)
