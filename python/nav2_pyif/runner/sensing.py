"""What the runner gives the controller besides the pose and the velocity, and keeps of what
the controller shows: the simulated laser as input ``scan`` (a sensor_msgs/LaserScan, shipped
as the plugin ships a topic listed in its ``inputs`` parameter: serialized, with the time it
arrived, only when new), and the controller's debug outputs, asked for every few cycles as
RViz subscribing would ask for them and kept as lines for the picture."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from nav2_pyif._ros_types import type_name_of
from nav2_pyif.runner.laser import Laser, LaserSpec
from nav2_pyif.runner.mapfile import OccupancyMap

#: The input name of the simulated scan (the plugin's ``inputs: ["scan"]``).
SCAN = "scan"


@dataclass(frozen=True)
class SensingConfig:
    """scan: the simulated laser (None: no scan input); scan_rate [Hz]: scans per second (at
    most one per control cycle); debug_every [s] of simulated time between the cycles that
    ask for the debug outputs (0: never)."""

    scan: LaserSpec | None = None
    scan_rate: float = 20.0
    debug_every: float = 0.5

    def __post_init__(self) -> None:
        if not self.scan_rate > 0:
            raise ValueError(f"the scan rate must be > 0 Hz, got {self.scan_rate}")
        if not self.debug_every >= 0:
            raise ValueError(f"debug_every must be >= 0 s, got {self.debug_every}")


#: One kept debug output: (simulated time [s], output name, lines: each (M, 2) x, y [m]).
DebugLines = tuple[float, str, list[np.ndarray]]


class Sensing:
    """Per control cycle: the new inputs and the debug outputs to ask for."""

    def __init__(self, config: SensingConfig, world: OccupancyMap, rate: float) -> None:
        self.laser = Laser(world, config.scan) if config.scan else None
        self.scan_every = max(1, round(rate / config.scan_rate))
        self.debug_every = max(1, round(config.debug_every * rate)) if config.debug_every else 0

    def inputs(self, cycle: int, stamp_s: float, x: float, y: float, yaw: float) -> Any:
        """name -> (message, receive time [ns]) of the inputs new at this cycle."""
        if self.laser is None or cycle % self.scan_every:
            return {}
        msg = self.laser.message(self.laser.ranges(x, y, yaw), stamp_s)
        return {SCAN: (msg, round(stamp_s * 1e9))}

    def wanted(self, cycle: int, declared: dict[str, str]) -> list[str]:
        """The debug outputs to ask for at this cycle: all declared ones, every few cycles."""
        return list(declared) if self.debug_every and cycle % self.debug_every == 0 else []


def lines_of(msg: Any) -> list[np.ndarray]:
    """A debug output message as (M, 2) x, y polylines to draw: a MarkerArray's markers (their
    points), a Path, a point (one (1, 2) line); other types are not drawn."""
    kind = type_name_of(msg)
    if kind == "visualization_msgs/msg/MarkerArray":
        return [_xy(m.points) for m in msg.markers if len(m.points)]
    if kind == "nav_msgs/msg/Path":
        return [_xy([p.pose.position for p in msg.poses])] if msg.poses else []
    if kind == "geometry_msgs/msg/PointStamped":
        return [_xy([msg.point])]
    return []


def _xy(points: Any) -> np.ndarray:
    return np.array([(p.x, p.y) for p in points], dtype=np.float64).reshape(-1, 2)
