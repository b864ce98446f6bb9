"""Nav2's goal/progress checking rules and the keep-out polygons, in Python: the cases of
nav2_controller's and nav2_costmap_2d's own behaviour."""

from __future__ import annotations

import math

import numpy as np
import pytest
from nav2_pyif import Combine
from nav2_pyif_planners.checkers import ProgressCheck, StoppedGoalCheck
from nav2_pyif_planners.keepout import (
    NO_INFORMATION,
    parse_polygons,
    polygon_mask,
)

pytestmark = pytest.mark.unit

GOAL = (2.0, 1.0, 0.0)
STILL = (0.0, 0.0, 0.0)


def test_goal_needs_position_heading_and_a_stopped_robot() -> None:
    check = StoppedGoalCheck()
    assert not check.is_goal_reached((1.0, 1.0, 0.0), GOAL, STILL)  # 1 m away
    assert not check.is_goal_reached((2.1, 1.0, 1.0), GOAL, STILL)  # heading off by 1 rad
    assert not check.is_goal_reached((2.1, 1.0, 0.1), GOAL, (0.4, 0.0, 0.0))  # still moving
    assert not check.is_goal_reached((2.1, 1.0, 0.1), GOAL, (0.0, 0.0, 0.5))  # still turning
    assert check.is_goal_reached((2.1, 1.0, 0.1), GOAL, (0.1, 0.1, 0.2))


def test_a_stateful_checker_keeps_the_position_once_reached_until_reset() -> None:
    check = StoppedGoalCheck()
    assert not check.is_goal_reached((2.0, 1.0, 1.0), GOAL, STILL)  # position latched
    assert check.is_goal_reached((2.4, 1.0, 0.0), GOAL, STILL)  # drifted out: still reached
    check.reset()
    assert not check.is_goal_reached((2.4, 1.0, 0.0), GOAL, STILL)
    stateless = StoppedGoalCheck(stateful=False)
    stateless.is_goal_reached((2.0, 1.0, 1.0), GOAL, STILL)
    assert not stateless.is_goal_reached((2.4, 1.0, 0.0), GOAL, STILL)


def test_symmetric_yaw_accepts_the_reverse_heading() -> None:
    backwards = (2.0, 1.0, math.pi - 0.1)
    assert not StoppedGoalCheck().is_goal_reached(backwards, GOAL, STILL)
    assert StoppedGoalCheck(symmetric_yaw_tolerance=True).is_goal_reached(backwards, GOAL, STILL)


def test_tolerances_are_what_get_tolerances_reports() -> None:
    t = StoppedGoalCheck(xy_goal_tolerance=0.3, rot_stopped_velocity=0.1).tolerances()
    assert (t.xy_goal_tolerance, t.yaw_goal_tolerance) == (0.3, 0.25)
    assert (t.trans_stopped_velocity, t.rot_stopped_velocity) == (0.25, 0.1)


def test_progress_fails_after_the_allowance_without_moving_far_enough() -> None:
    now = [0.0]
    check = ProgressCheck(required_movement_radius=0.5, movement_time_allowance=10.0)
    check.clock = lambda: now[0]
    assert check.check(0.0, 0.0)  # the baseline
    now[0] = 9.0
    assert check.check(0.4, 0.0)  # within the radius, within the allowance
    now[0] = 10.5
    assert not check.check(0.4, 0.0)  # 10.5 s without leaving the radius
    assert check.check(0.6, 0.0)  # moved: a new baseline
    now[0] = 20.0
    assert check.check(0.6, 0.1)
    now[0] = 21.0
    assert not check.check(0.6, 0.1)
    check.reset()
    assert check.check(0.6, 0.1)


def test_polygons_parse_like_nav2_footprints_and_bad_ones_say_why() -> None:
    polys = parse_polygons("[[[0, 0], [1, 0], [1, 1]], [[2, 2], [3, 2], [3, 3], [2, 3]]]")
    assert [p.shape for p in polys] == [(3, 2), (4, 2)]
    assert parse_polygons("") == []
    with pytest.raises(ValueError, match="polygon 0 needs at least three"):
        parse_polygons("[[[0, 0], [1, 0]]]")
    with pytest.raises(ValueError, match="not a list"):
        parse_polygons("[[0, 0], [1")


def test_a_polygon_covers_the_cells_whose_centres_are_inside() -> None:
    square = parse_polygons("[[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]]")
    mask = polygon_mask(square, origin=(0.0, 0.0), resolution=0.1, shape=(30, 30))
    assert mask.sum() == 100  # 1 m x 1 m at 10 cm
    assert mask[15, 15] and not mask[5, 5] and not mask[25, 15]
    # a window elsewhere on the map sees the same square at its own cells
    shifted = polygon_mask(square, origin=(1.0, 1.5), resolution=0.1, shape=(10, 10))
    assert shifted[:5].all() and not shifted[5:].any()
    triangle = parse_polygons("[[[0, 0], [2, 0], [0, 2]]]")
    tri = polygon_mask(triangle, origin=(0.0, 0.0), resolution=0.1, shape=(20, 20))
    assert abs(int(tri.sum()) - 190) <= 20  # about half the 2 m square


def test_combine_modes_as_nav2s_costmap_layer() -> None:
    master = np.array([[0, 100, NO_INFORMATION, 200]], np.uint8)
    layer = np.array([[50, 50, 50, NO_INFORMATION]], np.uint8)
    assert Combine.MAX.apply(master, layer).tolist() == [[50, 100, 50, 200]]
    assert Combine.MAX_KEEP_UNKNOWN.apply(master, layer).tolist() == [
        [50, 100, NO_INFORMATION, 200]
    ]
    assert Combine.OVERWRITE.apply(master, layer).tolist() == [[50, 50, 50, 200]]
    assert Combine.TRUE_OVERWRITE.apply(master, layer).tolist() == [[50, 50, 50, NO_INFORMATION]]
    with pytest.raises(ValueError, match="does not match"):
        Combine.MAX.apply(master, layer[:, :2])


def test_a_sub_window_sees_exactly_the_cells_of_the_whole_grid() -> None:
    """Each polygon is tested only within its bounding box: clipping it to any window gives
    the same cells as the whole grid has there."""
    rng = np.random.default_rng(7)
    for _ in range(50):
        polygons = [rng.uniform(-3.0, 3.0, (int(rng.integers(3, 7)), 2)) for _ in range(3)]
        whole = polygon_mask(polygons, origin=(-3.0, -3.0), resolution=0.1, shape=(60, 60))
        r0, c0 = (int(v) for v in rng.integers(0, 40, 2))
        corner = (-3.0 + c0 * 0.1, -3.0 + r0 * 0.1)
        window = polygon_mask(polygons, origin=corner, resolution=0.1, shape=(20, 17))
        assert (window == whole[r0 : r0 + 20, c0 : c0 + 17]).all()
