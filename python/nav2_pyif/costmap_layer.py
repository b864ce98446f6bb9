"""Base class of Python costmap layers: mirrors nav2_costmap_2d::Layer (a costmap's plugins).

Every costmap update, Nav2 asks each layer how far the update must reach (``update_bounds``),
then for its costs in the master grid's window that covers those bounds (``update_costs``):
the layer returns a uint8 window and how it combines with the master's costs. Only that
window crosses the wire.
"""

from __future__ import annotations

from abc import abstractmethod
from dataclasses import dataclass
from enum import Enum
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.plugin import PlannerPlugin

Bounds = tuple[float, float, float, float]  # min_x, min_y, max_x, max_y [m]
ByteArray = npt.NDArray[np.uint8]
NO_INFORMATION = 255  # nav2_costmap_2d::NO_INFORMATION


class Combine(str, Enum):
    """How a layer's window of costs meets the master grid's: nav2_costmap_2d::CostmapLayer's
    update modes (the C++ layer plugin applies them with those very functions). A layer cell
    of NO_INFORMATION (255) never changes the master, except in TRUE_OVERWRITE."""

    MAX = "max"  # updateWithMax: where the layer's is higher, or the master's unknown
    MAX_KEEP_UNKNOWN = "max_keep_unknown"  # updateWithMaxWithoutUnknownOverwrite
    OVERWRITE = "overwrite"  # updateWithOverwrite: the layer's, wherever it knows one
    TRUE_OVERWRITE = "true_overwrite"  # updateWithTrueOverwrite: the layer's, unknown too

    def apply(self, master: npt.NDArray[np.uint8], layer: npt.NDArray[np.uint8]) -> ByteArray:
        """The master window after the layer's window of costs is applied in this mode (what
        the C++ plugin leaves to Nav2's functions; the offline runner and tests use this)."""
        if master.shape != layer.shape:
            raise ValueError(
                f"layer window {layer.shape} does not match the master's {master.shape}"
            )
        if self is Combine.TRUE_OVERWRITE:
            return np.array(layer, dtype=np.uint8, copy=True)
        if self is Combine.OVERWRITE:
            return np.where(layer == NO_INFORMATION, master, layer).astype(np.uint8)
        known = layer != NO_INFORMATION
        higher = known & (layer > master) & (master != NO_INFORMATION)
        if self is Combine.MAX:
            higher |= known & (master == NO_INFORMATION)
        return np.where(higher, layer, master).astype(np.uint8)


@dataclass(frozen=True)
class LayerWindow:
    """The master grid's cells [min_i, max_i) x [min_j, max_j) to update."""

    min_i: int
    min_j: int
    max_i: int
    max_j: int
    origin_x: float  # the master grid's origin: cell (0, 0)'s corner [m]
    origin_y: float
    resolution: float  # m per cell

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) = (max_j - min_j, max_i - min_i): the shape to return."""
        return self.max_j - self.min_j, self.max_i - self.min_i

    @property
    def corner(self) -> tuple[float, float]:
        """World x, y [m] of the window's outer corner (cell (min_i, min_j)'s)."""
        return (
            self.origin_x + self.min_i * self.resolution,
            self.origin_y + self.min_j * self.resolution,
        )

    def cell_centres(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """(rows, cols) arrays of the world x and y [m] of each cell's centre."""
        rows, cols = self.shape
        x0, y0 = self.corner
        xs = x0 + (np.arange(cols) + 0.5) * self.resolution
        ys = y0 + (np.arange(rows) + 0.5) * self.resolution
        gx, gy = np.meshgrid(xs, ys)
        return gx, gy


class CostmapLayer(PlannerPlugin):
    """Subclass and implement ``update_costs``; ``configure`` is Nav2's ``onInitialize``.

    ``self.costmap`` is 0 x 0: a layer sees the master grid's geometry (``self.master``, from
    ``match_size``) and the windows it is asked for, not the master's costs.
    """

    plugin_type: ClassVar[PluginType] = PluginType.COSTMAP_LAYER
    #: The master grid: (size_x, size_y, resolution, origin_x, origin_y), None before Nav2 says.
    master: tuple[int, int, float, float, float] | None = None

    def update_bounds(
        self, robot_x: float, robot_y: float, robot_yaw: float, bounds: Bounds
    ) -> Bounds:
        """Grow ``bounds`` (world metres, the earlier layers') to cover every cell this layer
        will change; the robot's pose in the costmap's global frame. The default leaves them."""
        return bounds

    @abstractmethod
    def update_costs(self, window: LayerWindow) -> Any:
        """The layer's costs for ``window``: a uint8 array of ``window.shape`` (255 = no
        information: leaves the master's cost), or ``(costs, Combine)``; Combine.MAX when
        not said."""

    def match_size(
        self, size_x: int, size_y: int, resolution: float, origin_x: float, origin_y: float
    ) -> None:
        """The master grid was resized or moved. The default stores it in ``self.master``."""
        self.master = (size_x, size_y, resolution, origin_x, origin_y)

    def reset(self) -> None:
        """Nav2 resets the costmap (e.g. the clear-costmap service)."""
