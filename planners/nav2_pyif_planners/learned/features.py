"""What the policy sees, computed alike when recording and when driving: the laser scan
(min-pooled into sectors), the plan ahead in the robot frame and the current velocity."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from nav2_pyif.geometry import arc_lengths

SECTORS = 24  # scan sectors over a full turn (the nearest return in each)
SCAN_CLIP = 3.0  # [m] farther returns read as this: only the near field matters here
PLAN_POINTS = 8  # plan points ahead ...
PLAN_SPACING = 0.25  # [m] ... this far apart along the plan
SIZE = SECTORS + 2 * PLAN_POINTS + 2


def scan_sectors(ranges: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """(SECTORS,) nearest return per sector [m], clipped to SCAN_CLIP; sector 0 starts
    behind the robot (-pi) and they go counter-clockwise."""
    pooled: np.ndarray = scan_sectors_of([(ranges, angles)])[0]
    return pooled


def scan_sectors_of(scans: Sequence[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """(B, SECTORS): ``scan_sectors`` of each (ranges, angles). The scans whose beams point
    the same ways (a fleet of one sensor model) are pooled in one reduction: per scan, a
    Python-level loop over sectors costed a batched learned controller more than its
    forward pass."""
    out = np.full((len(scans), SECTORS), SCAN_CLIP)
    alike: dict[bytes, list[int]] = {}
    for i, (_, angles) in enumerate(scans):
        if len(angles):  # a scan without beams sees nothing nearer than SCAN_CLIP
            alike.setdefault(np.asarray(angles).tobytes(), []).append(i)
    for key, rows in alike.items():
        order, starts, sectors = _pooling(key, np.asarray(scans[rows[0]][1]))
        ranges = np.stack([scans[i][0] for i in rows])
        clipped = np.where(np.isfinite(ranges), ranges, SCAN_CLIP).clip(0.0, SCAN_CLIP)
        nearest = np.minimum.reduceat(clipped[:, order], starts, axis=1)
        out[np.ix_(np.asarray(rows), sectors)] = nearest
    return out


#: angles' bytes -> their pooling; a host serves few sensor models, so this stays small
_POOLINGS: dict[bytes, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}


def _pooling(key: bytes, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(beam order grouping each sector's beams, where each group starts, its sector) for
    the (non-empty) ``angles`` whose bytes are ``key``."""
    if key not in _POOLINGS:
        if len(_POOLINGS) >= 64:
            _POOLINGS.clear()
        sector = ((np.mod(angles + math.pi, 2 * math.pi)) / (2 * math.pi) * SECTORS).astype(int)
        sector = np.clip(sector, 0, SECTORS - 1)
        order = np.argsort(sector, kind="stable")
        grouped = sector[order]
        starts = np.flatnonzero(np.r_[True, grouped[1:] != grouped[:-1]])
        _POOLINGS[key] = (order, starts, grouped[starts])
    return _POOLINGS[key]


def plan_window(
    path_xy: np.ndarray,
    index: int,
    x: float,
    y: float,
    yaw: float,
    along: np.ndarray | None = None,
) -> np.ndarray:
    """(PLAN_POINTS, 2) plan points every PLAN_SPACING metres from ``index`` on, in the robot
    frame (the last point repeated past the plan's end). ``along``: the plan's arc length at
    each point (``Plan.along``, computed once per plan); measured here when not given."""
    if along is None:
        along = arc_lengths(path_xy)
    wanted = along[index] + PLAN_SPACING * np.arange(1, PLAN_POINTS + 1)
    ahead, from_here = path_xy[index:], along[index:]
    dx = np.interp(wanted, from_here, ahead[:, 0]) - x
    dy = np.interp(wanted, from_here, ahead[:, 1]) - y
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
    row: np.ndarray = features_of([(ranges, angles)], window[None], np.asarray([velocity]))[0]
    return row


def features_of(
    scans: Sequence[tuple[np.ndarray, np.ndarray]], windows: np.ndarray, velocities: np.ndarray
) -> np.ndarray:
    """(B, SIZE) float32: ``features`` of B robots from their (ranges, angles), their
    (B, PLAN_POINTS, 2) plan windows and (B, 2) velocities."""
    return np.concatenate(
        [scan_sectors_of(scans) / SCAN_CLIP, windows.reshape(len(scans), -1), velocities], axis=1
    ).astype(np.float32)
