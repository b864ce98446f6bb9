"""Client of a Python costmap layer: what nav2_pyif's C++ layer plugin does, in Python."""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt
from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.costmap_layer import Bounds, Combine, LayerWindow


class CostmapLayerClient(PluginClient):
    plugin_type = PluginType.COSTMAP_LAYER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "keepout")
        kwargs.setdefault("node", "local_costmap")
        super().__init__(*args, **kwargs)

    def match_size(
        self, size_x: int, size_y: int, resolution: float, origin_x: float, origin_y: float
    ) -> None:
        body = {
            "size_x": size_x,
            "size_y": size_y,
            "resolution": float(resolution),
            "origin_x": float(origin_x),
            "origin_y": float(origin_y),
        }
        self._call(Op.MATCH_SIZE, body)

    def update_bounds(self, robot: tuple[float, float, float], bounds: Bounds) -> Bounds:
        x, y, yaw = robot
        body = {"robot_x": float(x), "robot_y": float(y), "robot_yaw": float(yaw)}
        body.update(zip(("min_x", "min_y", "max_x", "max_y"), map(float, bounds), strict=True))
        reply = self._call(Op.UPDATE_BOUNDS, body)
        return reply["min_x"], reply["min_y"], reply["max_x"], reply["max_y"]

    def update_costs(self, window: LayerWindow) -> tuple[npt.NDArray[np.uint8], Combine]:
        """The layer's (rows, cols) uint8 costs for ``window`` and how they combine."""
        body = {
            "min_i": window.min_i,
            "min_j": window.min_j,
            "max_i": window.max_i,
            "max_j": window.max_j,
            "origin_x": float(window.origin_x),
            "origin_y": float(window.origin_y),
            "resolution": float(window.resolution),
        }
        reply = self._call(Op.UPDATE_COSTS, body)
        costs = np.frombuffer(reply["costs"], dtype=np.uint8)
        return costs.reshape(reply["height"], reply["width"]), Combine(reply["combine"])

    def reset(self) -> None:
        self._call(Op.RESET, {})
