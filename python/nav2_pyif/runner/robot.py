"""The simulated robot: a differential drive with acceleration limits, and the checks the
runner makes against the true (uninflated) map: collision and clearance."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from nav2_pyif.costmap import Costmap
from nav2_pyif.runner.mapfile import OCCUPIED, OccupancyMap

#: A 0.4 x 0.3 m rectangle (x forward), Nav2-style footprint, metres in the robot frame.
DEFAULT_FOOTPRINT = ((0.2, 0.15), (0.2, -0.15), (-0.2, -0.15), (-0.2, 0.15))


@dataclass
class DiffDrive:
    x: float
    y: float
    yaw: float
    v: float = 0.0  # [m/s]
    w: float = 0.0  # [rad/s]
    max_accel: float = 2.5  # [m/s^2]
    max_angular_accel: float = 3.2  # [rad/s^2]

    def step(self, cmd_v: float, cmd_w: float, dt: float) -> None:
        """Track the command within the acceleration limits, then integrate (midpoint)."""
        self.v += float(np.clip(cmd_v - self.v, -self.max_accel * dt, self.max_accel * dt))
        self.w += float(
            np.clip(cmd_w - self.w, -self.max_angular_accel * dt, self.max_angular_accel * dt)
        )
        mid = self.yaw + 0.5 * self.w * dt
        self.x += self.v * math.cos(mid) * dt
        self.y += self.v * math.sin(mid) * dt
        self.yaw = math.atan2(math.sin(self.yaw + self.w * dt), math.cos(self.yaw + self.w * dt))

    def stop(self) -> None:
        self.v = self.w = 0.0


#: How far [m] the clearance check looks: a clearance of this much means "nothing nearer".
CLEARANCE_REACH = 2.0


class WorldChecker:
    """Collision and clearance of the footprint against the occupied cells of the map."""

    def __init__(self, world: OccupancyMap, footprint: npt.ArrayLike) -> None:
        lethal = np.where(world.occupancy == OCCUPIED, Costmap.LETHAL, 0).astype(np.uint8)
        self.world = Costmap(
            lethal, world.resolution, world.origin_x, world.origin_y, footprint=footprint
        )
        self.outline = self.world.footprint_outline(spacing=world.resolution / 2)
        self._cells = np.column_stack(np.nonzero(world.occupancy == OCCUPIED)[::-1])
        self._centres = (
            self.world.map_to_world_array(self._cells) if len(self._cells) else np.zeros((0, 2))
        )

    def collides(self, x: float, y: float, yaw: float) -> bool:
        return bool(
            self.world.footprint_costs(np.array([x, y, yaw]), self.outline) >= Costmap.LETHAL
        )

    def clearance(self, x: float, y: float, yaw: float, reach: float = CLEARANCE_REACH) -> float:
        """Smallest distance [m] from the footprint outline to an occupied cell's edge
        (``reach`` when none is that close)."""
        near = self._centres[
            (np.abs(self._centres[:, 0] - x) < reach) & (np.abs(self._centres[:, 1] - y) < reach)
        ]
        if len(near) == 0:
            return reach
        c, s = math.cos(yaw), math.sin(yaw)
        pts = np.column_stack(
            [
                x + c * self.outline[:, 0] - s * self.outline[:, 1],
                y + s * self.outline[:, 0] + c * self.outline[:, 1],
            ]
        )
        d = np.linalg.norm(pts[:, None, :] - near[None], axis=-1).min()
        return max(0.0, float(d) - 0.5 * self.world.resolution)
