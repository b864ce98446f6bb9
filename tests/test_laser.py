"""The runner's simulated laser against geometry whose answer is known: a square room, an
open side, the sensor's mount, noise, and the LaserScan message it makes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from nav2_pyif.runner.laser import Laser, LaserSpec
from nav2_pyif.runner.mapfile import OCCUPIED, UNKNOWN, OccupancyMap

pytestmark = pytest.mark.unit

RES = 0.05


def _room(open_east: bool = False) -> OccupancyMap:
    """A 4 m x 4 m room (walls one cell thick on its border), origin at (0, 0)."""
    grid = np.zeros((80, 80), np.int8)
    grid[0, :] = grid[-1, :] = grid[:, 0] = OCCUPIED
    if not open_east:
        grid[:, -1] = OCCUPIED
    grid[30:50, 60:62] = UNKNOWN  # unknown cells do not stop a beam
    return OccupancyMap(grid, RES, 0.0, 0.0)


def test_beams_measure_the_distance_to_the_walls() -> None:
    spec = LaserSpec(beams=4, angle_min=0.0, angle_max=1.5 * math.pi, noise=0.0)
    ranges = Laser(_room(), spec).ranges(1.0, 2.0, 0.0)
    # east wall's cell starts at 3.95 m, west wall's ends at 0.05 m; north / south likewise
    assert ranges.dtype == np.float32
    assert ranges == pytest.approx([2.95, 1.95, 0.95, 1.95], abs=RES / 4 + 1e-6)


def test_the_robots_heading_and_the_mount_turn_and_move_the_scan() -> None:
    spec = LaserSpec(beams=1, angle_min=0.0, angle_max=0.0, noise=0.0, mount=(0.2, 0.0, 0.0))
    laser = Laser(_room(), spec)
    assert laser.ranges(1.0, 2.0, math.pi / 2)[0] == pytest.approx(1.95 - 0.2, abs=RES / 4)
    assert laser.ranges(1.0, 2.0, math.pi)[0] == pytest.approx(0.95 - 0.2, abs=RES / 4)


def test_nothing_in_range_reads_infinity_and_short_ranges_are_clipped() -> None:
    spec = LaserSpec(beams=1, angle_min=0.0, angle_max=0.0, noise=0.0, range_max=2.0)
    laser = Laser(_room(open_east=True), spec)
    assert np.isinf(laser.ranges(1.0, 2.0, 0.0)[0])  # out of the room's open side
    close = LaserSpec(beams=1, angle_min=math.pi, angle_max=math.pi, noise=0.0, range_min=0.5)
    assert Laser(_room(), close).ranges(0.2, 2.0, 0.0)[0] == pytest.approx(0.5)


def test_noise_is_gaussian_with_the_given_spread_and_reproducible() -> None:
    spec = LaserSpec(beams=2000, angle_min=-0.01, angle_max=0.01, noise=0.02)
    first = Laser(_room(), spec, seed=3).ranges(1.0, 2.0, 0.0)
    again = Laser(_room(), spec, seed=3).ranges(1.0, 2.0, 0.0)
    assert np.array_equal(first, again)
    assert float(np.std(first)) == pytest.approx(0.02, rel=0.15)
    assert float(np.mean(first)) == pytest.approx(2.95, abs=RES / 2)


def test_the_scan_is_a_laserscan_message() -> None:
    from sensor_msgs.msg import LaserScan

    spec = LaserSpec(beams=720)
    laser = Laser(_room(), spec)
    msg = laser.message(laser.ranges(2.0, 2.0, 0.0), stamp_s=12.5)
    assert isinstance(msg, LaserScan) and len(msg.ranges) == 720
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (12, 500_000_000)
    assert msg.angle_min + 719 * msg.angle_increment == pytest.approx(msg.angle_max)


def test_bad_specs_say_why() -> None:
    with pytest.raises(ValueError, match="at least one beam"):
        LaserSpec(beams=0)
    with pytest.raises(ValueError, match="range_min"):
        LaserSpec(range_min=9.0)
