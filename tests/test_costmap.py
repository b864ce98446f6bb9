"""Costmap view: Nav2's index and coordinate conventions, scalar and vectorised."""

from __future__ import annotations

import numpy as np
import pytest
from nav2_pyif import Costmap

from tests.conftest import make_costmap

pytestmark = pytest.mark.unit


def test_constants_match_nav2() -> None:
    assert (
        Costmap.FREE_SPACE,
        Costmap.INSCRIBED_INFLATED_OBSTACLE,
        Costmap.LETHAL_OBSTACLE,
        Costmap.NO_INFORMATION,
    ) == (0, 253, 254, 255)


def test_world_map_conversions_follow_costmap2d() -> None:
    grid = np.zeros((20, 30), np.uint8)  # size_y = 20, size_x = 30
    cm = Costmap(grid, 0.5, origin_x=-2.0, origin_y=1.0)
    assert (cm.size_x, cm.size_y) == (30, 20)
    assert cm.world_to_map(-2.0, 1.0) == (0, 0)
    assert cm.world_to_map(-1.51, 1.49) == (0, 0)
    assert cm.world_to_map(-1.5, 1.5) == (1, 1)
    assert cm.world_to_map(-2.01, 1.0) is None
    assert cm.world_to_map(-2.0 + 15.0, 1.0) is None  # x = size_x * resolution: outside
    assert cm.map_to_world(0, 0) == (-1.75, 1.25)  # cell centre
    assert cm.world_to_map(*cm.map_to_world(29, 19)) == (29, 19)


def test_vectorised_conversions_agree_with_scalar_ones() -> None:
    rng = np.random.default_rng(1)
    cm = Costmap(rng.integers(0, 256, (25, 35), dtype=np.uint8), 0.2, origin_x=-1, origin_y=-3)
    pts = rng.uniform(-3, 8, size=(500, 2))
    cells, inside = cm.world_to_map_array(pts)
    assert (cm.inside_world_array(pts) == inside).all()
    edges = [[-1.0, -3.0], [-1.0 + 35 * 0.2, -3.0], [-1.0, -3.0 + 25 * 0.2], [-1.0 - 1e-12, 0.0]]
    assert cm.inside_world_array(edges).tolist() == cm.world_to_map_array(edges)[1].tolist()
    for (x, y), cell, ok in zip(pts, cells, inside, strict=False):
        scalar = cm.world_to_map(x, y)
        assert ok == (scalar is not None)
        if scalar is not None:
            assert tuple(cell) == scalar
    costs = cm.costs_at_world(pts)
    expected = [cm.cost_at_world(x, y) for x, y in pts]
    assert costs.tolist() == expected
    assert np.allclose(
        cm.map_to_world_array(cells[inside]), [cm.map_to_world(*c) for c in cells[inside]]
    )


def test_cells_index_data_as_my_mx() -> None:
    grid = np.zeros((4, 6), np.uint8)
    grid[1, 4] = 254  # my = 1, mx = 4
    cm = Costmap(grid, 1.0)
    assert cm.cost(4, 1) == 254
    assert cm.cost_at_world(4.5, 1.5) == 254
    assert cm.cost_at_world(-1.0, 0.0) == Costmap.NO_INFORMATION


def test_wire_round_trip_is_a_read_only_zero_copy_view() -> None:
    cm = make_costmap(size=16, version=7)
    wire = cm.to_wire()
    back = Costmap.from_wire(wire)
    assert np.shares_memory(back.data, np.frombuffer(wire["data"], np.uint8))
    assert not back.data.flags.writeable
    assert np.array_equal(back.data, cm.data) and back.version == 7
    assert np.array_equal(back.footprint, cm.footprint)


def test_footprint_costs_vectorised_over_any_leading_shape() -> None:
    cm = make_costmap(size=40)  # lethal quadrant x, y >= 2.0 m
    poses = np.array([[[1.0, 1.0, 0.0], [1.9, 1.0, 0.0]], [[2.5, 2.5, 0.3], [1.0, 1.85, 1.57]]])
    costs = cm.footprint_costs(poses)
    assert costs.shape == (2, 2)
    assert costs[0, 0] == 0
    assert costs[1, 0] == Costmap.LETHAL
    # footprint is 0.4 m long: at x = 1.9 its front edge (x = 2.1) is still at y = 1.0 < 2.0
    assert costs[0, 1] == 0
    # rotated 90 degrees at y = 1.85: its front reaches y = 2.05 but x = 1.0 is free there
    assert costs[1, 1] == 0


def test_footprint_costs_at_the_map_edge_with_unknown_as_free() -> None:
    cm = make_costmap(size=40)  # 4 x 4 m, lethal quadrant x, y >= 2.0 m
    grid = cm.data.copy()
    grid[5, 5] = Costmap.NO_INFORMATION
    cm = Costmap(grid, 0.1, footprint=cm.footprint)
    # half the footprint beyond x = 4 m (off the map), the other half on lethal cells
    edge = np.array([[3.95, 3.0, 0.0]])
    assert cm.footprint_costs(edge)[0] == Costmap.NO_INFORMATION  # off-map counts unknown
    assert cm.footprint_costs(edge, unknown_as=0)[0] == Costmap.LETHAL  # the lethal half shows
    # wholly off the map, or on an unknown cell among free ones: free when unknown is free
    assert cm.footprint_costs(np.array([[9.0, 9.0, 0.0]]), unknown_as=0)[0] == 0
    assert cm.footprint_costs(np.array([[0.55, 0.55, 0.0]]), unknown_as=0)[0] == 0
    assert cm.footprint_costs(np.array([[0.55, 0.55, 0.0]]))[0] == Costmap.NO_INFORMATION


def test_bad_costmaps_are_refused_with_reasons() -> None:
    with pytest.raises(ValueError, match="2-D uint8"):
        Costmap(np.zeros((3, 3), np.int8), 0.1)
    with pytest.raises(ValueError, match="resolution"):
        Costmap(np.zeros((3, 3), np.uint8), 0.0)
