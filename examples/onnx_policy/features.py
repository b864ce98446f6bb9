"""What the policy sees and what it was fitted to: shared by the controller and make_model.py.

Features, (N, 3) float32: sin and cos of the heading error [rad] to the target (the carrot on
the plan, or the goal's heading once there) and the distance to the goal [m], capped at 1.
"""

from __future__ import annotations

from typing import Any

import numpy as np

MAX_SPEED = 0.4  # [m/s] what the teacher drives at, on a straight
MAX_TURN = 1.5  # [rad/s]


def features(heading_error: Any, goal_distance: Any) -> Any:
    """(N, 3) float32 policy inputs from (N,) heading errors [rad] and goal distances [m]."""
    e, d = np.asarray(heading_error, np.float64), np.asarray(goal_distance, np.float64)
    return np.column_stack([np.sin(e), np.cos(e), np.minimum(d, 1.0)]).astype(np.float32)


def teacher(heading_error: Any, goal_distance: Any) -> Any:
    """(N, 2) v [m/s], w [rad/s]: the hand-designed law the network is fitted to. Turn first
    (no speed while facing away), slow down over the last 0.3 m."""
    e, d = np.asarray(heading_error), np.asarray(goal_distance)
    v = MAX_SPEED * np.maximum(0.0, np.cos(e)) ** 2 * np.minimum(1.0, d / 0.3)
    w = MAX_TURN * np.tanh(2.0 * e)
    return np.column_stack([v, w])
