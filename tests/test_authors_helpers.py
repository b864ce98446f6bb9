"""The helpers the authors' API gives a planner so that an adapter does not copy them: the
costmap's obstacles as points, the footprint's radii and the inflation's costs, and the
geometry of poses and paths (nav2_pyif.geometry), checked against what they stand for."""

from __future__ import annotations

import math

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import Pose, PoseStamped, Quaternion
from nav2_pyif import Costmap
from nav2_pyif.runner.inflation import inflation_layer
from nav_msgs.msg import Path

pytestmark = pytest.mark.unit


def _quaternion(yaw: float) -> Quaternion:
    return Quaternion(z=math.sin(yaw / 2), w=math.cos(yaw / 2))


def _pose(x: float, y: float, yaw: float) -> PoseStamped:
    pose = PoseStamped()
    pose.pose.position.x, pose.pose.position.y = x, y
    pose.pose.orientation = _quaternion(yaw)
    return pose


def _grid(size: int = 20) -> np.ndarray:
    return np.zeros((size, size), np.uint8)


def test_obstacle_points_are_the_edge_cells_centres_in_the_world() -> None:
    data = _grid()
    data[5:10, 5:10] = Costmap.LETHAL  # a 5 x 5 block: 16 cells on its edge, 9 inside
    costmap = Costmap(data, 0.1, origin_x=-1.0, origin_y=2.0)
    edges = costmap.obstacle_points()
    every = costmap.obstacle_points(edges_only=False)
    assert edges.shape == (16, 2) and every.shape == (25, 2)
    assert np.allclose(every.min(axis=0), [-1.0 + 0.55, 2.0 + 0.55])  # cell (5, 5)'s centre
    inside = {(round(x, 2), round(y, 2)) for x, y in every} - {
        (round(x, 2), round(y, 2)) for x, y in edges
    }
    assert len(inside) == 9
    assert all(costmap.cost_at_world(x, y) == Costmap.LETHAL for x, y in edges)


def test_obstacle_points_on_the_maps_edge_unknown_and_the_threshold() -> None:
    data = _grid(6)
    data[:, 0] = Costmap.LETHAL  # a wall along the map's edge: every cell is an edge cell
    data[3, 3] = Costmap.NO_INFORMATION
    data[4, 4] = Costmap.INSCRIBED
    costmap = Costmap(data, 1.0)
    assert len(costmap.obstacle_points()) == 6
    assert len(costmap.obstacle_points(unknown_is_obstacle=True)) == 7
    assert len(costmap.obstacle_points(threshold=Costmap.INSCRIBED)) == 7
    assert costmap.obstacle_points(threshold=255, unknown_is_obstacle=False).shape == (0, 2)


def test_the_footprints_radii() -> None:
    rectangle = [[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]
    costmap = Costmap(_grid(), 0.05, footprint=rectangle)
    assert costmap.inscribed_radius == pytest.approx(0.2)
    assert costmap.circumscribed_radius == pytest.approx(math.hypot(0.3, 0.2))
    round_robot = Costmap(_grid(), 0.05, robot_radius=0.22)
    assert round_robot.inscribed_radius == round_robot.circumscribed_radius == 0.22


def test_inflation_cost_is_the_runners_inflation_layer() -> None:
    """One formula: the runner's inflation layer gives each cell the cost the API's helper
    gives its distance from the obstacle."""
    data = _grid(40)
    data[20, 20] = Costmap.LETHAL
    inflated = inflation_layer(Costmap(data, 0.05), 0.1, 0.6, 3.0)
    for cells in range(0, 12):
        distance = cells * 0.05
        expected = Costmap.inflation_cost(round(distance, 9), 0.1, 3.0)
        assert inflated.data[20, 20 + cells] == expected, cells
    assert Costmap.inflation_cost(0.0, 0.1, 3.0) == Costmap.LETHAL
    assert Costmap.inflation_cost(0.1, 0.1, 3.0) == Costmap.INSCRIBED
    assert Costmap.inflation_cost(0.2, 0.1, 3.0) == int(252 * math.exp(-0.3))


def test_circumscribed_cost_lets_no_cell_below_it_touch_the_robot() -> None:
    """Around one lethal cell inflated as Nav2 does, every cell costing less than
    circumscribed_cost has its centre beyond the footprint's circumscribed radius from the
    obstacle's: a robot there clears it at every heading (as Nav2's cell-centre distances
    measure it), while INSCRIBED, the round robot's threshold, lets the corners hit."""
    rectangle = [[0.3, 0.15], [0.3, -0.15], [-0.3, -0.15], [-0.3, 0.15]]
    data = _grid(60)
    data[30, 30] = Costmap.LETHAL
    static = Costmap(data, 0.05, footprint=rectangle)
    inflated = inflation_layer(static, static.inscribed_radius, 1.0, 3.0)
    obstacle = static.map_to_world_array([[30, 30]])[0]

    def nearest_centre(threshold: int) -> float:
        cells = np.argwhere(inflated.data < threshold)[:, ::-1]
        centres = static.map_to_world_array(cells)
        return float(np.hypot(*(centres - obstacle).T).min())

    threshold = inflated.circumscribed_cost(3.0)
    assert Costmap.INSCRIBED > threshold > 0
    assert nearest_centre(threshold) > static.circumscribed_radius
    assert nearest_centre(Costmap.INSCRIBED) < static.circumscribed_radius
    # a margin keeps every cell below it that much further out; one past the inflation's reach
    # leaves only the free cells
    wider = inflated.circumscribed_cost(3.0, margin=0.2)
    assert threshold > wider > 0
    assert nearest_centre(wider) > static.circumscribed_radius + 0.2
    assert nearest_centre(threshold) < static.circumscribed_radius + 0.2
    assert inflated.circumscribed_cost(3.0, margin=10.0) == 1
    assert nearest_centre(1) > 1.0  # the inflation radius


def test_geometry_of_poses_and_paths() -> None:
    assert api.yaw_of(_quaternion(2.5)) == pytest.approx(2.5)
    assert api.pose_xy_yaw(_pose(1.0, -2.0, -0.5)) == pytest.approx((1.0, -2.0, -0.5))
    bare = Pose()
    bare.orientation = _quaternion(1.0)
    assert api.pose_xy_yaw(bare)[2] == pytest.approx(1.0)
    path = Path(poses=[_pose(i * 0.5, 0.0, 0.1 * i) for i in range(5)])
    xy_yaw = api.path_xy_yaw(path)
    assert xy_yaw.shape == (5, 3) and xy_yaw[4, 0] == 2.0 and xy_yaw[3, 2] == pytest.approx(0.3)
    assert api.wrap(np.array([3 * math.pi, -3 * math.pi / 2])) == pytest.approx(
        [math.pi, math.pi / 2]
    )


def test_the_carrot_is_lookahead_metres_past_the_nearest_point() -> None:
    xy = np.column_stack([np.linspace(0.0, 4.0, 41), np.zeros(41)])  # 0.1 m apart
    point, index = api.carrot(xy, 1.02, 0.3, 0.55)
    assert index == 10 and point == pytest.approx([1.55, 0.0])
    point, index = api.carrot(xy, 0.5, 0.0, 0.5, start=index)  # progress never goes back
    assert index == 10 and point == pytest.approx([1.5, 0.0])
    assert api.carrot(xy, 3.9, 0.0, 2.0)[0] == pytest.approx([4.0, 0.0])  # past the end
    assert api.remaining_length(xy, 10) == pytest.approx(3.0)
    assert api.limit_speed(0.5, (50.0, True)) == 0.25
    assert api.limit_speed(0.5, (0.3, False)) == 0.3


def test_a_plans_arc_length_at_each_pose() -> None:
    xy = np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 4.0], [3.0, 5.0]])
    plan = api.Plan(xy, "map")
    assert plan.along.tolist() == [0.0, 5.0, 5.0, 6.0]  # a repeated pose adds nothing
    assert api.Plan(np.zeros((1, 7)), "map").along.tolist() == [0.0]
    assert api.Plan(np.zeros((0, 7)), "map").along.tolist() == []
