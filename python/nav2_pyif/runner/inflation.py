"""Costs from an occupancy map, as Nav2's static + inflation layers compute them.

cost(d) for a cell at distance d [m] from the nearest lethal cell:
  d == 0                       -> 254 LETHAL
  d <= inscribed_radius        -> 253 INSCRIBED
  d <= inflation_radius        -> floor(252 * exp(-cost_scaling_factor * (d - inscribed_radius)))
  otherwise                    -> 0; unknown cells stay 255 NO_INFORMATION.
Distances come from a cached kernel of cell offsets, like the layer's cached distances.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from nav2_pyif.costmap import Costmap, Inflation
from nav2_pyif.runner.mapfile import OCCUPIED, UNKNOWN, OccupancyMap


def obstacle_distance(
    lethal: npt.NDArray[np.bool_], resolution: float, max_distance: float
) -> npt.NDArray[np.float64]:
    """Distance [m] from each cell centre to the nearest lethal cell centre, capped at
    ``max_distance`` (cells farther away get +inf)."""
    reach = int(np.ceil(max_distance / resolution))
    size_y, size_x = lethal.shape
    distance = np.full(lethal.shape, np.inf)
    padded = np.zeros((size_y + 2 * reach, size_x + 2 * reach), bool)
    padded[reach : reach + size_y, reach : reach + size_x] = lethal
    for dy in range(-reach, reach + 1):
        for dx in range(-reach, reach + 1):
            d = np.hypot(dx, dy) * resolution
            if d > max_distance:
                continue
            shifted = padded[reach + dy : reach + dy + size_y, reach + dx : reach + dx + size_x]
            np.minimum(distance, np.where(shifted, d, np.inf), out=distance)
    return distance


def inflate(
    occupancy: OccupancyMap,
    inscribed_radius: float = 0.22,
    inflation_radius: float = 0.55,
    cost_scaling_factor: float = 3.0,
    footprint: npt.ArrayLike | None = None,
    robot_radius: float = 0.0,
    frame_id: str = "map",
    version: int = 1,
) -> Costmap:
    """The inflated costmap of a whole occupancy map: the static layer, then inflation."""
    static = static_layer(occupancy, footprint, robot_radius, frame_id, version)
    return inflation_layer(static, inscribed_radius, inflation_radius, cost_scaling_factor)


def static_layer(
    occupancy: OccupancyMap,
    footprint: npt.ArrayLike | None = None,
    robot_radius: float = 0.0,
    frame_id: str = "map",
    version: int = 1,
) -> Costmap:
    """Nav2's static layer: LETHAL where occupied, NO_INFORMATION where unknown, else free."""
    costs = np.zeros(occupancy.occupancy.shape, np.uint8)
    costs[occupancy.occupancy == UNKNOWN] = Costmap.NO_INFORMATION
    costs[occupancy.occupancy == OCCUPIED] = Costmap.LETHAL
    return Costmap(
        costs,
        occupancy.resolution,
        occupancy.origin_x,
        occupancy.origin_y,
        frame_id,
        footprint=footprint,
        robot_radius=robot_radius,
        version=version,
    )


def inflation_layer(
    master: Costmap,
    inscribed_radius: float = 0.22,
    inflation_radius: float = 0.55,
    cost_scaling_factor: float = 3.0,
) -> Costmap:
    """Nav2's inflation layer over the layers before it: costs around every lethal cell,
    raising the master's (an unknown cell takes an inflation cost when it gets one)."""
    lethal = master.data == Costmap.LETHAL
    # cell distances are multiples of the resolution: round away float noise (3 * 0.05 m)
    distance = np.round(obstacle_distance(lethal, master.resolution, inflation_radius), 9)
    reached = distance <= inflation_radius  # farther (inf included): no cost
    costs = np.zeros(lethal.shape, np.uint8)
    costs[reached] = Costmap.inflation_cost(
        distance[reached], inscribed_radius, cost_scaling_factor
    )
    costs[lethal] = Costmap.LETHAL
    unknown = master.data == Costmap.NO_INFORMATION
    merged = np.where(unknown & (costs == 0), master.data, np.maximum(costs, master.data))
    merged[unknown & (costs > 0)] = costs[unknown & (costs > 0)]
    inflated = master.with_costs(merged.astype(np.uint8))
    inflated.inflation = Inflation(inflation_radius, cost_scaling_factor)  # what Nav2's says
    return inflated


def window(costmap: Costmap, x: float, y: float, size_m: float, version: int) -> Costmap:
    """A rolling local costmap: ``size_m`` square centred on (x, y), origin snapped to cells
    (Nav2's rolling_window). Outside the map reads NO_INFORMATION."""
    cells = round(size_m / costmap.resolution)
    mx0 = int(np.floor((x - costmap.origin_x) / costmap.resolution)) - cells // 2
    my0 = int(np.floor((y - costmap.origin_y) / costmap.resolution)) - cells // 2
    out = np.full((cells, cells), Costmap.NO_INFORMATION, np.uint8)
    sx0, sy0 = max(mx0, 0), max(my0, 0)
    sx1, sy1 = min(mx0 + cells, costmap.size_x), min(my0 + cells, costmap.size_y)
    if sx1 > sx0 and sy1 > sy0:
        out[sy0 - my0 : sy1 - my0, sx0 - mx0 : sx1 - mx0] = costmap.data[sy0:sy1, sx0:sx1]
    return Costmap(
        out,
        costmap.resolution,
        costmap.origin_x + mx0 * costmap.resolution,
        costmap.origin_y + my0 * costmap.resolution,
        costmap.frame_id,
        footprint=costmap.footprint,
        robot_radius=costmap.robot_radius,
        version=version,
        inflation=costmap.inflation,
    )
