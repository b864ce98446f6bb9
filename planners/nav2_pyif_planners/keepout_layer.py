"""A keep-out costmap layer: polygons (a parameter ``ros2 param set`` can change) made lethal
in the costmap, in NumPy (``keepout``), served to any Nav2 costmap as a layer plugin::

    planner-host --key nav2_pyif/robot1/keepout \\
        --planner nav2_pyif_planners.keepout_layer:KeepOutLayer

Parameters: ``polygons`` ("[[[x, y], [x, y], [x, y], ...], ...]" in the costmap's global
frame, metres, as Nav2 writes footprints), ``cost`` (254, lethal) and ``combine`` (max,
max_keep_unknown, overwrite or true_overwrite).
"""

from __future__ import annotations

import numpy as np
from nav2_pyif import Combine, CostmapLayer, LayerWindow
from nav2_pyif.costmap_layer import Bounds
from nav2_pyif.params import ParamValue

from nav2_pyif_planners.keepout import NO_INFORMATION, parse_polygons, polygon_mask


class KeepOutLayer(CostmapLayer):
    def configure(self) -> None:
        p = self.params
        p.declare("polygons", "[]", "keep-out polygons [[[x, y], ...], ...] [m]")
        p.declare("cost", 254, "cost inside the polygons (254: lethal)")
        p.declare("combine", "max", "max, max_keep_unknown, overwrite or true_overwrite")
        self.stale: Bounds | None = None  # where removed polygons were: cleared once
        self._read()

    def _read(self) -> None:
        self.polygons = parse_polygons(str(self.params["polygons"]))
        self.cost = int(self.params["cost"])
        if not 0 <= self.cost <= 254:
            raise ValueError(f"cost must be 0..254, got {self.cost}")
        self.combine = Combine(str(self.params["combine"]))

    def on_parameters_changed(self, changed: dict[str, ParamValue]) -> None:
        before = self._extent()
        self._read()
        if before is not None:  # the next update covers where the old polygons were
            self.stale = _union(self.stale, before)

    def _extent(self) -> Bounds | None:
        if not self.polygons:
            return None
        points = np.concatenate(self.polygons)
        (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
        return float(x0), float(y0), float(x1), float(y1)

    def update_bounds(
        self, robot_x: float, robot_y: float, robot_yaw: float, bounds: Bounds
    ) -> Bounds:
        grown = _union(bounds, self._extent())
        grown, self.stale = _union(grown, self.stale), None
        return grown

    def update_costs(self, window: LayerWindow) -> tuple[np.ndarray, Combine]:
        mask = polygon_mask(self.polygons, window.corner, window.resolution, window.shape)
        costs = np.full(window.shape, NO_INFORMATION, dtype=np.uint8)
        costs[mask] = self.cost
        return costs, self.combine


def _union(a: Bounds | None, b: Bounds | None) -> Bounds:
    if a is None:
        assert b is not None
        return b
    if b is None:
        return a
    return min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3])
