"""The costmap as Python sees it: a read-only NumPy view of Nav2's uint8 costs plus geometry.

Indices follow Nav2's Costmap2D: cell (mx, my) is ``data[my, mx]``; world coordinates are in
``frame_id``; (origin_x, origin_y) is the outer corner of cell (0, 0).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from nav2_pyif_protocol.arrays import ByteArray, FloatArray, costmap_grid, pack_xy, unpack_xy


@dataclass(frozen=True)
class Inflation:
    """The costmap's inflation layer's parameters (Nav2's names): costs decay from 253 at the
    footprint's inscribed radius to 0 at ``inflation_radius``, as
    ``252 * exp(-cost_scaling_factor * (d - inscribed_radius))`` (``Costmap.inflation_cost``)."""

    inflation_radius: float  # [m]
    cost_scaling_factor: float  # [1/m]

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> Inflation | None:
        """From configure's ``nav2_params``; None unless both are there."""
        radius, factor = params.get("inflation_radius"), params.get("cost_scaling_factor")
        if isinstance(radius, int | float) and isinstance(factor, int | float):
            return cls(float(radius), float(factor))
        return None


class Costmap:
    FREE_SPACE: ClassVar[int] = 0
    INSCRIBED_INFLATED_OBSTACLE: ClassVar[int] = 253
    LETHAL_OBSTACLE: ClassVar[int] = 254
    NO_INFORMATION: ClassVar[int] = 255
    # Short aliases.
    FREE: ClassVar[int] = 0
    INSCRIBED: ClassVar[int] = 253
    LETHAL: ClassVar[int] = 254

    def __init__(
        self,
        data: npt.ArrayLike,
        resolution: float,
        origin_x: float = 0.0,
        origin_y: float = 0.0,
        frame_id: str = "map",
        footprint: npt.ArrayLike | None = None,
        robot_radius: float = 0.0,
        version: int = 0,
        inflation: Inflation | None = None,
    ) -> None:
        """``data``: (size_y, size_x) uint8 costs; ``footprint``: (K, 2) x, y [m], robot frame;
        ``inflation``: the inflation layer's parameters, None when not known."""
        grid = np.asarray(data)
        if grid.ndim != 2 or grid.dtype != np.uint8:
            raise ValueError(
                f"costmap data must be a 2-D uint8 array, got {grid.dtype} {grid.shape}"
            )
        if not resolution > 0:
            raise ValueError(f"costmap resolution must be > 0, got {resolution}")
        self.data: ByteArray = grid
        self.resolution = float(resolution)
        self.origin_x = float(origin_x)
        self.origin_y = float(origin_y)
        self.frame_id = frame_id
        self.footprint: FloatArray = (
            np.zeros((0, 2))
            if footprint is None
            else np.asarray(footprint, np.float64).reshape(-1, 2)
        )
        self.robot_radius = float(robot_radius)
        self.version = version
        #: The inflation layer's parameters (from Nav2's configuration, or the offline
        #: runner's), None when the plugin did not say: ``circumscribed_cost()`` uses them.
        self.inflation = inflation

    def with_costs(self, data: npt.ArrayLike, version: int | None = None) -> Costmap:
        """Another grid of costs over this costmap's cells (same geometry and robot)."""
        return Costmap(
            data,
            self.resolution,
            self.origin_x,
            self.origin_y,
            self.frame_id,
            footprint=self.footprint,
            robot_radius=self.robot_radius,
            version=self.version if version is None else version,
            inflation=self.inflation,
        )

    # --- wire ---------------------------------------------------------------------------
    @classmethod
    def from_wire(cls, wire: dict[str, Any], inflation: Inflation | None = None) -> Costmap:
        """Zero-copy: ``data`` is a read-only view of the received bytes. (The inflation's
        parameters travel in configure, not with each costmap.)"""
        return cls(
            costmap_grid(wire["data"], wire["size_x"], wire["size_y"]),
            wire["resolution"],
            wire["origin_x"],
            wire["origin_y"],
            wire["frame_id"],
            unpack_xy(wire["footprint"]),
            wire["robot_radius"],
            wire["version"],
            inflation,
        )

    def to_wire(self) -> dict[str, Any]:
        return {
            "version": self.version,
            "frame_id": self.frame_id,
            "size_x": self.size_x,
            "size_y": self.size_y,
            "resolution": self.resolution,
            "origin_x": self.origin_x,
            "origin_y": self.origin_y,
            "data": np.ascontiguousarray(self.data).tobytes(),
            "footprint": pack_xy(self.footprint),
            "robot_radius": self.robot_radius,
        }

    # --- geometry -----------------------------------------------------------------------
    @property
    def size_x(self) -> int:
        return int(self.data.shape[1])

    @property
    def size_y(self) -> int:
        return int(self.data.shape[0])

    @property
    def size_in_meters(self) -> tuple[float, float]:
        return self.size_x * self.resolution, self.size_y * self.resolution

    def world_to_map(self, wx: float, wy: float) -> tuple[int, int] | None:
        """World [m] -> cell (mx, my), or None outside the map (Nav2's worldToMap)."""
        if wx < self.origin_x or wy < self.origin_y:
            return None
        mx = int((wx - self.origin_x) / self.resolution)
        my = int((wy - self.origin_y) / self.resolution)
        if mx < self.size_x and my < self.size_y:
            return mx, my
        return None

    def map_to_world(self, mx: float, my: float) -> tuple[float, float]:
        """Cell -> world coordinates of its centre [m] (Nav2's mapToWorld)."""
        return (
            self.origin_x + (mx + 0.5) * self.resolution,
            self.origin_y + (my + 0.5) * self.resolution,
        )

    def world_to_map_array(
        self, xy: npt.ArrayLike
    ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.bool_]]:
        """(..., 2) world x, y [m] -> ((..., 2) int64 mx, my; (...,) bool inside). Outside
        cells are clipped into the map so they can index ``data``; use the mask."""
        pts = np.asarray(xy, dtype=np.float64)
        mx = np.floor((pts[..., 0] - self.origin_x) / self.resolution).astype(np.int64)
        my = np.floor((pts[..., 1] - self.origin_y) / self.resolution).astype(np.int64)
        inside = (mx >= 0) & (my >= 0) & (mx < self.size_x) & (my < self.size_y)
        np.clip(mx, 0, self.size_x - 1, out=mx)
        np.clip(my, 0, self.size_y - 1, out=my)
        return np.stack([mx, my], axis=-1), inside

    def inside_world_array(self, xy: npt.ArrayLike) -> npt.NDArray[np.bool_]:
        """(..., 2) world x, y [m] -> (...,) bool: the point lies in the map (world_to_map_array's
        mask without its cells: floor(u) >= 0 is u >= 0, floor(u) < size is u < size)."""
        pts = np.asarray(xy, dtype=np.float64)
        u = (pts[..., 0] - self.origin_x) / self.resolution
        v = (pts[..., 1] - self.origin_y) / self.resolution
        inside: npt.NDArray[np.bool_] = (u >= 0.0) & (u < self.size_x)
        return inside & (v >= 0.0) & (v < self.size_y)

    def _cells_and_mask(
        self, wx: npt.NDArray[np.float64], wy: npt.NDArray[np.float64]
    ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.bool_]]:
        """Flat cell indices (my * size_x + mx, clipped) and the inside mask."""
        mx = np.floor((wx - self.origin_x) * (1.0 / self.resolution)).astype(np.int64)
        my = np.floor((wy - self.origin_y) * (1.0 / self.resolution)).astype(np.int64)
        inside = (mx >= 0) & (my >= 0) & (mx < self.size_x) & (my < self.size_y)
        np.clip(mx, 0, self.size_x - 1, out=mx)
        np.clip(my, 0, self.size_y - 1, out=my)
        return my * self.size_x + mx, inside

    def map_to_world_array(self, mxy: npt.ArrayLike) -> FloatArray:
        """(N, 2) cells -> (N, 2) world coordinates of the cell centres [m]."""
        cells = np.asarray(mxy, dtype=np.float64)
        world: FloatArray = (cells + 0.5) * self.resolution + np.array(
            [self.origin_x, self.origin_y]
        )
        return world

    # --- costs --------------------------------------------------------------------------
    def cost(self, mx: int, my: int) -> int:
        return int(self.data[my, mx])

    def cost_at_world(self, wx: float, wy: float) -> int:
        """Cost under a world point; NO_INFORMATION outside the map."""
        cell = self.world_to_map(wx, wy)
        return self.NO_INFORMATION if cell is None else self.cost(*cell)

    def costs_at_world(self, xy: npt.ArrayLike) -> ByteArray:
        """(..., 2) world points -> (...,) uint8 costs; NO_INFORMATION outside the map."""
        pts = np.asarray(xy, dtype=np.float64)
        flat, inside = self._cells_and_mask(pts[..., 0], pts[..., 1])
        costs = self.data.ravel()[flat]
        costs[~inside] = self.NO_INFORMATION
        return costs

    def footprint_outline(self, spacing: float | None = None) -> FloatArray:
        """(M, 2) points on the footprint's edges (or the robot_radius circle) in the robot
        frame, about ``spacing`` apart (default: the map resolution), plus the centre."""
        step = spacing or self.resolution
        if len(self.footprint) >= 3:
            corners = self.footprint
            pts = [np.zeros((1, 2))]
            for a, b in zip(corners, np.roll(corners, -1, axis=0), strict=False):
                n = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
                t = np.arange(n)[:, None] / n
                pts.append(a + t * (b - a))
            return np.concatenate(pts)
        radius = self.robot_radius
        n = max(8, int(np.ceil(2 * np.pi * radius / step))) if radius > 0 else 0
        angles = np.arange(n) * (2 * np.pi / max(n, 1))
        ring = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
        return np.concatenate([np.zeros((1, 2)), ring])

    def footprint_costs(
        self,
        poses: npt.ArrayLike,
        outline: FloatArray | None = None,
        unknown_as: int | None = None,
    ) -> ByteArray:
        """Max cost under the footprint at each pose: (..., 3) x, y, yaw -> (...,) uint8.

        Vectorised over any leading shape (e.g. MPPI's (rollouts, steps, 3)). Cells off the
        map count as NO_INFORMATION; with ``unknown_as`` (e.g. 0 for "unknown is free"), those
        and NO_INFORMATION cells count as that value instead, point by point, so a lethal
        cell under the rest of the footprint still shows."""
        p = np.asarray(poses, dtype=np.float64)
        pts = self.footprint_outline() if outline is None else outline
        c, s = np.cos(p[..., 2:3]), np.sin(p[..., 2:3])
        wx = p[..., 0:1] + c * pts[:, 0] - s * pts[:, 1]
        wy = p[..., 1:2] + s * pts[:, 0] + c * pts[:, 1]
        flat, inside = self._cells_and_mask(wx, wy)
        costs = self.data.ravel()[flat]
        costs[~inside] = self.NO_INFORMATION
        if unknown_as is not None:
            costs[costs == self.NO_INFORMATION] = unknown_as
        worst: ByteArray = costs.max(axis=-1)
        return worst

    def obstacle_points(
        self,
        threshold: int = 254,
        edges_only: bool = True,
        unknown_is_obstacle: bool = False,
    ) -> FloatArray:
        """(N, 2) world x, y [m] of the centres of the cells costing ``threshold`` or more,
        for planners that take obstacles as points (DWA, potential fields, MPC constraints).

        ``edges_only`` keeps only the cells with a free 4-neighbour (or on the map's edge):
        what a distance check needs, a fraction of the cells of a large obstacle.
        NO_INFORMATION cells count only with ``unknown_is_obstacle``."""
        hit = self.data >= threshold
        if not unknown_is_obstacle:
            hit &= self.data != self.NO_INFORMATION
        if edges_only:
            padded = np.pad(hit, 1, constant_values=False)
            inside = padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
            hit &= ~inside
        my, mx = np.nonzero(hit)
        return self.map_to_world_array(np.stack([mx, my], axis=1))

    # --- the footprint and the inflation's costs ----------------------------------------
    @property
    def inscribed_radius(self) -> float:
        """[m] the largest circle about the robot's centre inside its footprint (Nav2's
        ``calculateMinAndMaxDistances``); ``robot_radius`` for a round robot."""
        if len(self.footprint) < 3:
            return self.robot_radius
        a, b = self.footprint, np.roll(self.footprint, -1, axis=0)
        edge = b - a
        t = np.clip(-(a * edge).sum(axis=1) / np.maximum((edge * edge).sum(axis=1), 1e-12), 0, 1)
        nearest = a + t[:, None] * edge
        return float(np.hypot(nearest[:, 0], nearest[:, 1]).min())

    @property
    def circumscribed_radius(self) -> float:
        """[m] the smallest circle about the robot's centre holding its footprint."""
        if len(self.footprint) < 3:
            return self.robot_radius
        return float(np.hypot(self.footprint[:, 0], self.footprint[:, 1]).max())

    @classmethod
    def inflation_cost(
        cls, distance: npt.ArrayLike, inscribed_radius: float, cost_scaling_factor: float
    ) -> ByteArray:
        """The cost Nav2's InflationLayer gives a cell ``distance`` [m] from an obstacle
        (``computeCost``): LETHAL on it, INSCRIBED within ``inscribed_radius``, then
        ``252 * exp(-cost_scaling_factor * (distance - inscribed_radius))``. Any shape."""
        d = np.asarray(distance, dtype=np.float64)
        decay = (cls.INSCRIBED_INFLATED_OBSTACLE - 1) * np.exp(
            -cost_scaling_factor * (d - inscribed_radius)
        )
        cost = np.where(d <= inscribed_radius, cls.INSCRIBED_INFLATED_OBSTACLE, decay)
        cost = np.where(d <= 0.0, cls.LETHAL_OBSTACLE, cost)
        costs: ByteArray = cost.astype(np.uint8)
        return costs

    def circumscribed_cost(
        self, cost_scaling_factor: float | None = None, *, margin: float = 0.0
    ) -> int:
        """The cost at the footprint's circumscribed radius: a cell costing less cannot touch
        the robot whatever its heading, so a global planner for a non-round robot that keeps
        below it plans paths the controller can follow (Nav2's Smac planners and MPPI use this
        threshold; 253, INSCRIBED, is only right for a round robot). ``margin`` [m]: the cost
        that far beyond the circumscribed radius instead, for a planner whose paths should
        keep clear of obstacles by more than the footprint (at least 1: a free cell is always
        below it). ``cost_scaling_factor`` [1/m]: by default the inflation layer's
        (``self.inflation``: Nav2's, or the offline runner's); raises ValueError when neither
        is known."""
        if cost_scaling_factor is None:
            if self.inflation is None:
                raise ValueError(
                    "the inflation layer's cost_scaling_factor is not known here (a plugin "
                    "older than configure's nav2_params, or a costmap without an inflation "
                    "layer): pass your Nav2 YAML's as circumscribed_cost(cost_scaling_factor)"
                )
            cost_scaling_factor = self.inflation.cost_scaling_factor
        cost = self.inflation_cost(
            self.circumscribed_radius + margin, self.inscribed_radius, cost_scaling_factor
        )
        return max(1, int(cost))

    # --- ROS ----------------------------------------------------------------------------
    def to_occupancy_grid(self) -> Any:
        """A nav_msgs/OccupancyGrid with the raw costs (cast to int8, as Nav2's costmap
        publisher does not: values > 127 read negative; read ``data`` here instead)."""
        from nav_msgs.msg import OccupancyGrid  # imported lazily: costly and rarely needed

        grid = OccupancyGrid()
        grid.header.frame_id = self.frame_id
        grid.info.resolution = self.resolution
        grid.info.width = self.size_x
        grid.info.height = self.size_y
        grid.info.origin.position.x = self.origin_x
        grid.info.origin.position.y = self.origin_y
        grid.data = self.data.astype(np.int8, copy=False).ravel().tolist()
        return grid

    def __repr__(self) -> str:
        return (
            f"Costmap({self.size_x}x{self.size_y} @ {self.resolution} m, origin "
            f"({self.origin_x}, {self.origin_y}), frame {self.frame_id!r}, v{self.version})"
        )
