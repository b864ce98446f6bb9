"""The run's picture and file names: the legend leaves the map alone, the controller's debug
outputs can be seen, runs with other plugins write other files."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from nav2_pyif.runner.cli import default_stem
from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.plot import figure
from nav2_pyif.runner.run import SimConfig, SimResult, prepare
from nav2_pyif.runner.swaps import Swap

pytestmark = pytest.mark.unit


def driven(result: SimResult, cycles: int = 200) -> SimResult:
    """A straight drive along the office corridor, the carrot 0.4 m ahead every 10 cycles."""
    result.trajectory = [(0.05 * i, 3.0 + 0.05 * i, 7.0, 0.0, 0.5, 0.0) for i in range(cycles)]
    result.plan = np.array([[3.0 + 0.05 * i, 7.0, 0.0] for i in range(cycles + 10)])
    result.debug = [
        (t, "lookahead_point", [np.array([[x + 0.4, y]])])
        for t, x, y, *_ in result.trajectory[::10]
    ]
    return result


def test_the_legend_is_outside_the_map() -> None:
    result = driven(prepare(SimConfig(map=map_path("cluttered"))))
    fig = figure(result)
    try:
        fig.canvas.draw()
        world = fig.axes[0]
        legend = world.get_legend()
        assert legend is not None
        box, drawn = legend.get_window_extent(), world.get_window_extent()
        assert not box.overlaps(drawn), (box, drawn)
        assert fig.bbox.contains(box.x0, box.y0) and fig.bbox.contains(box.x1, box.y1)
    finally:
        plt.close(fig)


def test_lookahead_points_show_over_the_driven_path() -> None:
    # They lie on the path, 0.4 m ahead of the robot: drawn under it, they were lost.
    fig = figure(driven(prepare(SimConfig(map=map_path("office")))))
    try:
        lines = {line.get_label(): line for line in fig.axes[0].get_lines()}
        points, path = lines["lookahead_point (debug output)"], lines["driven"]
        assert points.get_zorder() > path.get_zorder()
        assert points.get_markersize() > path.get_linewidth()  # wider than the path [pt]
        assert (points.get_alpha() or 1.0) == 1.0
    finally:
        plt.close(fig)


def test_runs_with_other_plugins_write_other_files() -> None:
    office = map_path("office")
    assert default_stem(prepare(SimConfig(map=office))) == "office_pure_pursuit"
    with_plugins = prepare(
        SimConfig(map=office, plugins={"smoother": "simple_smoother", "layer": "my.layers:Zone"})
    )
    assert default_stem(with_plugins) == "office_pure_pursuit_simple_smoother_my.layers.Zone"
    other_planner = prepare(SimConfig(map=office, planner="my.planners:Rrt"))
    assert default_stem(other_planner) == "office_pure_pursuit_my.planners.Rrt"


def test_a_hot_swap_is_marked_on_the_map_and_the_timeline() -> None:
    result = driven(prepare(SimConfig(map=map_path("office"))))
    result.sim_time = result.trajectory[-1][0]
    result.swaps = [Swap(4.0, "controller", "nav2_pyif_planners.mppi:MPPI")]
    fig = figure(result)
    try:
        world, speed = fig.axes[0], fig.axes[2]
        marks = [line for line in world.get_lines() if line.get_label() == "hot swap"]
        assert len(marks) == 1
        where = np.asarray(marks[0].get_xydata())[0]
        assert np.allclose(where, (3.0 + 0.05 * 80, 7.0))  # where the robot was at 4 s
        assert any("controller → mppi at 4.0 s" in t.get_text() for t in world.texts)
        assert "hot swap" in [line.get_label() for line in speed.get_lines()]
        assert "pure_pursuit → mppi + astar" in " ".join(world.get_title().split())
    finally:
        plt.close(fig)
