"""The DWA's geometry in NumPy: constant-twist arcs and nearest distances."""

from __future__ import annotations

from typing import Any

import numpy as np

STEP = 0.05  # [s] between rolled-out poses: 2.5 cm at 0.5 m/s, half a cell


def arcs(x: float, y: float, yaw: float, v: Any, w: Any, horizon: float) -> Any:
    """(K, T, 3) poses x, y [m], yaw [rad] of K constant (v [m/s], w [rad/s]) arcs from
    (x, y, yaw), every STEP seconds from STEP up to ``horizon``."""
    t = np.arange(1, round(horizon / STEP) + 1) * STEP  # (T,)
    v, w = np.asarray(v)[:, None], np.asarray(w)[:, None]
    heading = yaw + w * t  # (K, T)
    turning = np.abs(w) > 1e-6  # exact arcs; straight lines where w is ~0
    radius = np.where(turning, v / np.where(turning, w, 1.0), 0.0)
    px = np.where(turning, radius * (np.sin(heading) - np.sin(yaw)), v * t * np.cos(yaw))
    py = np.where(turning, radius * (np.cos(yaw) - np.cos(heading)), v * t * np.sin(yaw))
    return np.stack([x + px, y + py, heading], axis=-1)


def nearest_distance(points: Any, others: Any) -> Any:
    """(K, T) [m] from each of (K, T, 2) points to the nearest of (M, 2) ``others``; inf
    when there are none."""
    if len(others) == 0:
        return np.full(points.shape[:2], np.inf)
    return np.linalg.norm(points[:, :, None, :] - others[None, None], axis=-1).min(axis=2)
