"""The NumPy path smoother against Nav2's SimpleSmoother: the same fixed point as its
pose-by-pose sweep (transliterated here from simple_smoother.cpp), fixed segment ends, cusps
kept, no point pushed onto a lethal cell, orientations along the new path, a time limit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from nav2_pyif import Costmap
from nav2_pyif_planners.smoothing import (
    SmootherSettings,
    SmoothingTimedOut,
    approximate_orientations,
    directional_segments,
    smooth_path,
)

pytestmark = pytest.mark.unit


def _zigzag(n: int = 40) -> np.ndarray:
    x = np.linspace(0.0, 4.0, n)
    y = 0.02 * (-1.0) ** np.arange(n)  # gentle: steps never point back (no cusps)
    y[0] = y[-1] = 0.0
    return np.column_stack([x, y, np.zeros(n)])


def _roughness(xy: np.ndarray) -> float:
    return float(np.square(np.diff(xy, 2, axis=0)).sum())


def _nav2_sequential(xy: np.ndarray, s: SmootherSettings) -> np.ndarray:
    """simple_smoother.cpp's smoothImpl without a costmap, pose by pose, for comparison."""
    original, path = xy.copy(), np.array(xy, dtype=np.float64)
    for _ in range(1 + (s.refinement_num if s.do_refinement else 0)):
        change, its = s.tolerance, 0
        while change >= s.tolerance:
            its += 1
            if its >= s.max_its:
                break
            change = 0.0
            for i in range(1, len(path) - 1):
                for j in range(2):
                    y_i = path[i, j]
                    path[i, j] += s.w_data * (original[i, j] - y_i) + s.w_smooth * (
                        path[i + 1, j] + path[i - 1, j] - 2.0 * y_i
                    )
                    change += abs(path[i, j] - y_i)
        original = path.copy()
    return path


def test_reaches_the_fixed_point_of_nav2s_sweep_and_keeps_the_ends() -> None:
    poses = _zigzag()
    smoothed = smooth_path(poses)
    assert np.allclose(smoothed[[0, -1], :2], poses[[0, -1], :2])
    assert _roughness(smoothed[:, :2]) < 0.01 * _roughness(poses[:, :2])
    reference = _nav2_sequential(poses[:, :2], SmootherSettings())
    assert np.abs(smoothed[:, :2] - reference).max() < 1e-6


def test_a_straight_path_stays_put() -> None:
    poses = np.column_stack([np.linspace(0, 3, 20), np.full(20, 1.0), np.zeros(20)])
    assert np.allclose(smooth_path(poses), poses)


def test_a_cusp_splits_the_path_and_stays_where_it_was() -> None:
    forward = np.column_stack([np.linspace(0, 2, 11), 0.05 * (-1.0) ** np.arange(11)])
    back = np.column_stack([np.linspace(2, 1, 6)[1:], np.linspace(0.05, 1.0, 6)[1:]])
    xy = np.vstack([forward, back])
    poses = np.column_stack([xy, np.zeros(len(xy))])
    assert directional_segments(poses)[0] == (0, 10)
    smoothed = smooth_path(poses)
    assert np.allclose(smoothed[10, :2], poses[10, :2])  # the cusp itself
    assert _roughness(smoothed[:11, :2]) < _roughness(poses[:11, :2])


def test_a_turn_in_place_is_its_own_segment() -> None:
    poses = np.array([[0, 0, 0], [1, 0, 0], [1, 0, math.pi / 2], [1, 1, math.pi / 2]], float)
    assert directional_segments(poses) == [(0, 1), (1, 3)]


def test_no_point_is_pushed_onto_a_lethal_cell() -> None:
    # An L-shaped path hugging an obstacle's corner: smoothing would cut the corner.
    grid = np.zeros((60, 60), np.uint8)
    grid[31:, :29] = Costmap.LETHAL  # x < 2.9 m and y >= 3.1 m; the path's corner: (3, 3)
    costmap = Costmap(grid, 0.1)
    leg1 = np.column_stack([np.linspace(0.5, 3.0, 26), np.full(26, 3.0)])
    leg2 = np.column_stack([np.full(25, 3.0), np.linspace(3.1, 5.5, 25)])
    xy = np.vstack([leg1, leg2])
    poses = np.column_stack([xy, np.zeros(len(xy))])
    free = smooth_path(poses)
    assert np.any(costmap.costs_at_world(free[:, :2]) == Costmap.LETHAL), "cut the corner"
    safe = smooth_path(poses, costs=costmap.costs_at_world)
    assert not np.any(costmap.costs_at_world(safe[:, :2]) == Costmap.LETHAL)
    assert _roughness(safe[:, :2]) < _roughness(poses[:, :2])


def test_orientations_follow_the_new_path_and_reverse_on_a_reversing_segment() -> None:
    xy = np.column_stack([np.linspace(0, 1, 5), np.linspace(0, 1, 5)])
    forward = approximate_orientations(np.column_stack([xy, np.zeros(5)]))
    assert np.allclose(forward[:-1, 2], math.pi / 4)
    backward = approximate_orientations(np.column_stack([xy, np.full(5, -3 * math.pi / 4)]))
    assert np.allclose(backward[:-1, 2], -3 * math.pi / 4)


def test_a_time_limit_raises_with_the_path_so_far() -> None:
    with pytest.raises(SmoothingTimedOut) as raised:
        smooth_path(_zigzag(), max_time=-1.0)
    assert raised.value.path.shape == (40, 3)


def test_bad_shapes_are_refused() -> None:
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        smooth_path(np.zeros((5, 2)))
