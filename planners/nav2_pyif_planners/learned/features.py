"""What the policy sees, computed alike when recording and when driving: the laser scan
(min-pooled into sectors), the plan ahead in the robot frame and the current velocity."""

from __future__ import annotations

import math

import numpy as np

SECTORS = 24  # scan sectors over a full turn (the nearest return in each)
SCAN_CLIP = 3.0  # [m] farther returns read as this: only the near field matters here
PLAN_POINTS = 8  # plan points ahead ...
PLAN_SPACING = 0.25  # [m] ... this far apart along the plan
SIZE = SECTORS + 2 * PLAN_POINTS + 2


def scan_sectors(ranges: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """(SECTORS,) nearest return per sector [m], clipped to SCAN_CLIP; sector 0 starts
    behind the robot (-pi) and they go counter-clockwise."""
    r = np.where(np.isfinite(ranges), ranges, SCAN_CLIP).clip(0.0, SCAN_CLIP)
    sector = ((np.mod(angles + math.pi, 2 * math.pi)) / (2 * math.pi) * SECTORS).astype(int)
    out = np.full(SECTORS, SCAN_CLIP)
    np.minimum.at(out, np.clip(sector, 0, SECTORS - 1), r)
    return out


def plan_window(path_xy: np.ndarray, index: int, x: float, y: float, yaw: float) -> np.ndarray:
    """(PLAN_POINTS, 2) plan points every PLAN_SPACING metres from ``index`` on, in the robot
    frame (the last point repeated past the plan's end)."""
    ahead = path_xy[index:]
    if len(ahead) == 1:
        points = np.repeat(ahead, PLAN_POINTS, axis=0)
    else:
        seg = np.hypot(*np.diff(ahead, axis=0).T)
        along = np.concatenate([[0.0], np.cumsum(seg)])
        wanted = PLAN_SPACING * np.arange(1, PLAN_POINTS + 1)
        points = np.column_stack(
            [np.interp(wanted, along, ahead[:, 0]), np.interp(wanted, along, ahead[:, 1])]
        )
    dx, dy = points[:, 0] - x, points[:, 1] - y
    c, s = math.cos(yaw), math.sin(yaw)
    return np.column_stack([c * dx + s * dy, -s * dx + c * dy])


def features(
    ranges: np.ndarray,
    angles: np.ndarray,
    path_xy: np.ndarray,
    index: int,
    pose: tuple[float, float, float],
    velocity: tuple[float, float],
) -> np.ndarray:
    """(SIZE,) float32: scan sectors / SCAN_CLIP, the plan window [m], v [m/s], w [rad/s]."""
    window = plan_window(path_xy, index, *pose)
    return np.concatenate(
        [scan_sectors(ranges, angles) / SCAN_CLIP, window.ravel(), np.asarray(velocity)]
    ).astype(np.float32)
