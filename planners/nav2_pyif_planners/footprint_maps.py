"""The footprint's cost at any pose with one lookup: per-heading maximum maps.

``Costmap.footprint_costs`` reads the map once per outline point (9 to 20 reads per pose).
A sampling controller scores tens of thousands of poses per cycle, and on a CPU those reads
are most of its time (the JAX MPPI: 60 % of its kernel). The maps here hold, for each of a few
headings, the largest cost under the footprint's outline placed at every cell, computed once
per costmap version; a pose then costs one read: its cell, its nearest heading.

What a read is, exactly: ``footprint_costs`` (with ``unknown_as=0``) of the pose moved to the
centre of its cell and turned to the nearest map heading. Map headings are 22.5 degrees apart
(16 per turn); a round footprint (``robot_radius``) needs one map, a polygon that a half turn
maps onto itself (a rectangle) 8, any other polygon 16. So a read can differ from the pose's
own outline cost by that of a cell next to an outline point (measured: 92 % of random poses
read the same cost); the outline's points are themselves up to 0.2 m apart.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from nav2_pyif import Costmap
from nav2_pyif_protocol.arrays import ByteArray, FloatArray

TURN = 16  # map headings per turn, 22.5 degrees apart; a power of two (a bit mask wraps them)


@dataclass(frozen=True)
class FootprintMaps:
    """``layers[h, row, col]``: the largest cost under the footprint at heading
    ``h * 2 pi / TURN`` with its centre in padded cell (col, row); unknown and off-map cells
    count as free. A pose at heading index ``i`` (its yaw in TURN-ths of a turn, rounded)
    reads map ``i mod headings``: 1 map for a round footprint, 8 for a centrally symmetric
    polygon, 16 for any other. The padding (a ring of cells around the map, free at its outer
    edge) lets a pose off the map still see the part of its footprint on it, and a pose beyond
    the padding read the free outer edge once its cell is clipped."""

    layers: ByteArray  # (headings, padded rows, padded cols)
    origin: FloatArray  # (2,) world x, y [m] of the padded map's cell (0, 0) corner
    resolution: float  # [m] per cell

    @property
    def headings(self) -> int:
        return int(self.layers.shape[0])

    def costs(self, poses: np.ndarray) -> ByteArray:
        """(..., 3) x, y, yaw -> (...,) uint8: the footprint's cost at each pose (NumPy)."""
        p = np.asarray(poses, dtype=np.float64)
        _, rows, cols = self.layers.shape
        col = np.clip(np.floor((p[..., 0] - self.origin[0]) / self.resolution), 0, cols - 1)
        row = np.clip(np.floor((p[..., 1] - self.origin[1]) / self.resolution), 0, rows - 1)
        heading = np.rint(p[..., 2] * (TURN / (2 * np.pi))).astype(np.int64)
        picked: ByteArray = self.layers[
            heading & (self.headings - 1), row.astype(np.int64), col.astype(np.int64)
        ]
        return picked


def footprint_maps(costmap: Costmap, outline: FloatArray) -> FootprintMaps:
    """The per-heading maximum maps of ``costmap`` for ``outline`` ((M, 2) points in the robot
    frame, as ``Costmap.footprint_outline`` gives)."""
    round_footprint = len(costmap.footprint) < 3
    if round_footprint:
        headings = 1
    else:
        headings = TURN // 2 if _half_turn_symmetric(costmap.footprint) else TURN
    resolution = costmap.resolution
    reach = math.ceil(float(np.abs(outline).max(initial=0.0)) / resolution) + 1
    pad = reach + 1  # the outermost ring stays free: no offset reaches it from the map
    free = np.where(costmap.data == Costmap.NO_INFORMATION, 0, costmap.data).astype(np.uint8)
    padded = np.pad(free, pad)
    layers = np.zeros((headings, *padded.shape), np.uint8)
    for h in range(headings):
        angle = h * 2 * np.pi / TURN
        c, s = np.cos(angle), np.sin(angle)
        # a point at offset v (in cells) from the centre of cell i lies in cell i + floor(v + 1/2)
        col = np.floor((c * outline[:, 0] - s * outline[:, 1]) / resolution + 0.5)
        row = np.floor((s * outline[:, 0] + c * outline[:, 1]) / resolution + 0.5)
        for dx, dy in set(zip(col.astype(int).tolist(), row.astype(int).tolist(), strict=True)):
            _raise_to_shifted(layers[h], padded, dx, dy)
    origin = np.array([costmap.origin_x, costmap.origin_y]) - pad * resolution
    return FootprintMaps(layers, origin, resolution)


def _half_turn_symmetric(polygon: FloatArray) -> bool:
    """The polygon's corners, turned half a turn about the robot's centre, are its corners."""
    corners = np.round(np.asarray(polygon, dtype=np.float64), 9)
    return bool(
        np.array_equal(np.unique(corners, axis=0), np.unique(np.round(-corners, 9), axis=0))
    )


def _raise_to_shifted(layer: ByteArray, padded: ByteArray, dx: int, dy: int) -> None:
    """layer[row, col] = max(layer[row, col], padded[row + dy, col + dx]) where that exists."""
    rows, cols = padded.shape
    out_rows, in_rows = slice(max(0, -dy), rows - max(0, dy)), slice(max(0, dy), rows - max(0, -dy))
    out_cols, in_cols = slice(max(0, -dx), cols - max(0, dx)), slice(max(0, dx), cols - max(0, -dx))
    np.maximum(layer[out_rows, out_cols], padded[in_rows, in_cols], out=layer[out_rows, out_cols])
