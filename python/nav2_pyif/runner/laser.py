"""A simulated 2-D laser scanner on the runner's true map: each beam marches from the sensor
in steps of a quarter cell until it meets an occupied cell, then Gaussian noise is added, as
a planar lidar's `sensor_msgs/LaserScan` would read. Beams that meet nothing within
`range_max` read +inf (REP 117's "no return"); unknown cells let beams through."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from nav2_pyif._messages import ns_to_stamp
from nav2_pyif.runner.mapfile import OCCUPIED, OccupancyMap

FloatArray = npt.NDArray[np.float32]


@dataclass(frozen=True)
class LaserSpec:
    """The scanner: `beams` evenly over [angle_min, angle_max] (radians, 0 = forward), ranges
    in [range_min, range_max] metres, noise standard deviation in metres, and where it sits on
    the robot (x, y forward/left of the base, yaw)."""

    beams: int = 360
    angle_min: float = -math.pi
    angle_max: float = math.pi * (1 - 2 / 360)  # a 360-beam full circle without a duplicate
    range_min: float = 0.05
    range_max: float = 8.0
    noise: float = 0.01
    mount: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        if self.beams < 1:
            raise ValueError(f"a laser needs at least one beam, got {self.beams}")
        if not 0.0 <= self.range_min < self.range_max:
            raise ValueError(f"range_min {self.range_min} must be in [0, {self.range_max})")
        if self.noise < 0.0:
            raise ValueError(f"noise must be >= 0, got {self.noise}")

    @property
    def angle_increment(self) -> float:
        return 0.0 if self.beams == 1 else (self.angle_max - self.angle_min) / (self.beams - 1)

    @property
    def angles(self) -> npt.NDArray[np.float64]:
        return self.angle_min + self.angle_increment * np.arange(self.beams, dtype=np.float64)


class Laser:
    """Scans of `world` with `spec`; `seed` makes the noise reproducible."""

    def __init__(self, world: OccupancyMap, spec: LaserSpec = LaserSpec(), seed: int = 0) -> None:
        self.world, self.spec = world, spec
        self._rng = np.random.default_rng(seed)
        step = world.resolution / 4
        self._along = np.arange(step, spec.range_max + step, step)  # (S,) sample distances
        self._occupied = world.occupancy == OCCUPIED

    def ranges(self, x: float, y: float, yaw: float) -> FloatArray:
        """(beams,) float32 ranges from the robot at (x, y, yaw) in the map frame."""
        mx, my, myaw = self.spec.mount
        sx = x + mx * math.cos(yaw) - my * math.sin(yaw)
        sy = y + mx * math.sin(yaw) + my * math.cos(yaw)
        heading = yaw + myaw + self.spec.angles  # (B,)
        px = sx + np.cos(heading)[:, None] * self._along  # (B, S)
        py = sy + np.sin(heading)[:, None] * self._along
        world, res = self.world, self.world.resolution
        cx = np.floor((px - world.origin_x) / res).astype(np.int64)
        cy = np.floor((py - world.origin_y) / res).astype(np.int64)
        inside = (cx >= 0) & (cx < world.size_x) & (cy >= 0) & (cy < world.size_y)
        hit = np.zeros(px.shape, dtype=bool)
        hit[inside] = self._occupied[cy[inside], cx[inside]]
        first = np.argmax(hit, axis=1)
        ranges = np.where(hit.any(axis=1), self._along[first], np.inf)
        if self.spec.noise > 0.0:
            ranges = ranges + self._rng.normal(0.0, self.spec.noise, ranges.shape)
        ranges = np.where(
            np.isfinite(ranges), np.clip(ranges, self.spec.range_min, self.spec.range_max), ranges
        )
        return ranges.astype(np.float32)

    def message(self, ranges: FloatArray, stamp_s: float, frame_id: str = "base_scan") -> Any:
        """The scan as a `sensor_msgs/msg/LaserScan` (what a Nav2 robot's driver publishes)."""
        from sensor_msgs.msg import LaserScan

        msg = LaserScan()
        msg.header.frame_id = frame_id
        msg.header.stamp = ns_to_stamp(round(stamp_s * 1e9))
        spec = self.spec
        msg.angle_min, msg.angle_max = spec.angle_min, spec.angle_max
        msg.angle_increment = spec.angle_increment
        msg.range_min, msg.range_max = spec.range_min, spec.range_max
        msg.ranges = ranges.tolist()
        return msg
