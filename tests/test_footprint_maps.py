"""The per-heading footprint maps (one read per pose) against the outline reads they replace
(``Costmap.footprint_costs``): a read is exactly the outline's cost with the pose moved to its
cell's centre and its nearest map heading, and most poses read their own outline cost."""

from __future__ import annotations

import numpy as np
import pytest
from nav2_pyif import Costmap
from nav2_pyif_planners.footprint_maps import TURN, footprint_maps

pytestmark = pytest.mark.unit

RESOLUTION = 0.05
RECTANGLE = np.array([[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]])
WEDGE = np.array([[0.35, 0.0], [-0.2, -0.25], [-0.2, 0.25]])  # no half-turn symmetry


def scattered_obstacles(seed: int) -> np.ndarray:
    """A 100 x 100 map: free, 30 lethal blocks, an unknown patch on the left edge."""
    rng = np.random.default_rng(seed)
    data = np.zeros((100, 100), np.uint8)
    for row, col in rng.integers(0, 100, (30, 2)):
        data[row : row + 5, col : col + 3] = Costmap.LETHAL
    data[50:60, 0:10] = Costmap.NO_INFORMATION
    return data


def random_poses(rng: np.random.Generator, count: int) -> np.ndarray:
    """Poses over the map and 1 m around it, at any yaw."""
    yaw = rng.uniform(-7.0, 7.0, count)
    xy = rng.uniform(-3.5, 3.5, (count, 2))
    return np.column_stack([xy, yaw])


def snapped(poses: np.ndarray, costmap: Costmap, maps_held: int) -> np.ndarray:
    """Each pose moved to its cell's centre and turned to its nearest map heading."""
    cell = np.floor((poses[:, :2] - [costmap.origin_x, costmap.origin_y]) / RESOLUTION)
    centre = (cell + 0.5) * RESOLUTION + [costmap.origin_x, costmap.origin_y]
    step = 2 * np.pi / TURN
    yaw = np.rint(poses[:, 2] / step) * step if maps_held > 1 else np.zeros(len(poses))
    return np.column_stack([centre, yaw])


@pytest.mark.parametrize(
    ("footprint", "radius", "maps_held"),
    [(None, 0.25, 1), (RECTANGLE, 0.0, TURN // 2), (WEDGE, 0.0, TURN)],
    ids=["round", "rectangle", "wedge"],
)
def test_a_read_is_the_outline_cost_at_the_cells_centre_and_nearest_heading(
    footprint: np.ndarray | None, radius: float, maps_held: int
) -> None:
    costmap = Costmap(
        scattered_obstacles(1), RESOLUTION, -2.5, -2.5, footprint=footprint, robot_radius=radius
    )
    outline = costmap.footprint_outline(spacing=0.2)
    maps = footprint_maps(costmap, outline)
    assert maps.headings == maps_held
    poses = random_poses(np.random.default_rng(2), 20_000)
    read = maps.costs(poses)
    at_centre = costmap.footprint_costs(snapped(poses, costmap, maps_held), outline, unknown_as=0)
    # all but the points that fall exactly on a cell's edge, where rounding in the last bit
    # decides (11 of 20 000 poses for the wedge)
    assert (read == at_centre).mean() > 0.999
    # and the pose's own outline cost, most of the time: they differ near an obstacle's edge
    own = costmap.footprint_costs(poses, outline, unknown_as=0)
    assert (read == own).mean() > 0.85


def test_poses_far_off_the_map_read_free_and_unknown_counts_as_free() -> None:
    data = np.full((20, 20), Costmap.NO_INFORMATION, np.uint8)
    data[0, 0] = Costmap.LETHAL
    costmap = Costmap(data, RESOLUTION, 0.0, 0.0, footprint=RECTANGLE)
    maps = footprint_maps(costmap, costmap.footprint_outline(spacing=0.2))
    far = np.array([[-50.0, 3.0, 0.5], [40.0, -40.0, 2.0], [0.5, 0.5, 0.0]])
    assert maps.costs(far).tolist() == [0, 0, 0]
    # a pose off the map, its footprint's front edge on the lethal corner cell, sees it
    off_the_edge = np.array([[-0.275, 0.025, 0.0]])
    outline = costmap.footprint_outline(spacing=0.2)
    assert costmap.footprint_costs(off_the_edge, outline, unknown_as=0).tolist() == [Costmap.LETHAL]
    assert maps.costs(off_the_edge).tolist() == [Costmap.LETHAL]
