"""A Python costmap layer (the reference keep-out layer) served by a real planner host over
real Zenoh sessions on loopback: bounds, the window's costs, parameter changes, errors."""

from __future__ import annotations

from typing import Any

import nav2_pyif as api
import pytest
from nav2_pyif import Combine, LayerWindow
from nav2_pyif.client import CostmapLayerClient

from tests.test_smoother_and_checker_hosts import GENEROUS, no_costmap

pytestmark = pytest.mark.integration

LAYER = "nav2_pyif/test_robot/keepout"
SQUARE = "[[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]]"
NONE = (1e30, 1e30, -1e30, -1e30)  # Nav2's bounds before any layer grew them


def layer(start_host: Any, zsession_factory: Any, **params: Any) -> CostmapLayerClient:
    spec = "nav2_pyif_planners.keepout_layer:KeepOutLayer"
    host = start_host("--key", LAYER, "--planner", spec)
    client = CostmapLayerClient(
        zsession_factory(host.endpoint), LAYER, no_costmap(), params=params, timeouts=GENEROUS
    )
    assert client.wait_for_host(15), host.log()
    client.configure()
    client.activate()
    return client


def test_keepout_polygons_become_lethal_cells_of_the_window(
    start_host: Any, zsession_factory: Any
) -> None:
    client = layer(start_host, zsession_factory, polygons=SQUARE)
    client.match_size(400, 400, 0.05, -10.0, -10.0)
    assert client.update_bounds((0.0, 0.0, 0.0), NONE) == (1.0, 1.0, 2.0, 2.0)
    assert client.update_bounds((0.0, 0.0, 0.0), (-1.0, 0.0, 1.5, 5.0)) == (-1.0, 0.0, 2.0, 5.0)
    # the master's cells 210..250 cover x 0.5 .. 2.5 m
    window = LayerWindow(210, 210, 250, 250, -10.0, -10.0, 0.05)
    costs, combine = client.update_costs(window)
    assert combine is Combine.MAX and costs.shape == (40, 40)
    inside = costs == 254
    assert inside.sum() == 20 * 20  # 1 m x 1 m at 5 cm
    assert (costs[~inside] == 255).all()  # no information: the master keeps its cost
    assert inside[10:30, 10:30].all()  # rows are y, columns x, from the window's corner


def test_ros2_param_set_moves_the_polygons_and_clears_where_they_were(
    start_host: Any, zsession_factory: Any
) -> None:
    client = layer(start_host, zsession_factory, polygons=SQUARE)
    moved = "[[[-2.0, -2.0], [-1.0, -2.0], [-1.5, -1.0]]]"
    assert client.set_parameters({"polygons": moved, "combine": "overwrite"}) == {}
    # once: the old square's extent too, so the costmap resets it
    assert client.update_bounds((0.0, 0.0, 0.0), NONE) == (-2.0, -2.0, 2.0, 2.0)
    assert client.update_bounds((0.0, 0.0, 0.0), NONE) == (-2.0, -2.0, -1.0, -1.0)
    costs, combine = client.update_costs(LayerWindow(0, 0, 40, 40, -2.0, -2.0, 0.05))
    assert combine is Combine.OVERWRITE and 0 < int((costs == 254).sum()) < 20 * 20
    with pytest.raises(api.ControllerException, match="polygon 0 needs at least three"):
        client.set_parameters({"polygons": "[[[0, 0], [1, 1]]]"})


def test_a_bad_combine_mode_is_refused_and_the_layer_keeps_working(
    start_host: Any, zsession_factory: Any
) -> None:
    client = layer(start_host, zsession_factory, polygons=SQUARE)
    with pytest.raises(api.ControllerException, match="'maximum' is not a valid Combine"):
        client.set_parameters({"combine": "maximum"})  # `ros2 param set` fails with this
    costs, combine = client.update_costs(LayerWindow(20, 20, 40, 40, 0.0, 0.0, 0.05))
    assert combine is Combine.MAX and (costs == 254).all()


def test_a_seed_style_layer_is_a_module_with_update_costs(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", LAYER, "--module", "seed_layer")
    client = CostmapLayerClient(
        zsession_factory(host.endpoint), LAYER, no_costmap(), timeouts=GENEROUS
    )
    assert client.wait_for_host(15), host.log()
    client.configure()
    assert client.update_bounds((0.0, 0.0, 0.0), NONE) == NONE  # no update_bounds function
    costs, combine = client.update_costs(LayerWindow(0, 0, 4, 2, -0.1, 0.0, 0.05))
    assert combine is Combine.MAX
    assert costs.tolist() == [[254, 254, 255, 255], [254, 254, 255, 255]]
    assert "update_bounds has no delegate" in host.log()
