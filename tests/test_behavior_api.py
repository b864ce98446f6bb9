"""The behaviour authors' API without a host: arc simulation, footprint collision checks,
goal fields, and the reference FreestBackUp's choice of heading on hand-made costmaps."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest
from nav2_pyif import Command, Costmap, arc
from nav2_pyif._context import PluginContext
from nav2_pyif.params import Parameters
from nav2_pyif_planners.free_backup import FreestBackUp

pytestmark = pytest.mark.unit

FOOTPRINT = [[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]


def attached(grid: np.ndarray) -> FreestBackUp:
    behavior = FreestBackUp()
    costmap = Costmap(grid, 0.05, frame_id="odom", version=1, footprint=FOOTPRINT)
    log = logging.getLogger("test")
    context = PluginContext("backup", "behavior_server", "odom", "base_link", costmap,
                            Parameters({}), log)  # fmt: skip
    behavior._attach(context)
    behavior.configure()
    return behavior


def test_arc_is_exact_for_straight_lines_and_circles() -> None:
    straight = arc(1.0, 2.0, math.pi / 2, -0.2, 0.0, 1.0, 0.25)
    np.testing.assert_allclose(straight[:, 0], 1.0, atol=1e-12)
    np.testing.assert_allclose(straight[:, 1], 2.0 - 0.2 * np.array([0.25, 0.5, 0.75, 1.0]))
    circle = arc(0.0, 0.0, 0.0, 0.5, 0.5, 2.0 * math.pi / 0.5, 0.01)  # one full turn, r = 1
    np.testing.assert_allclose(np.hypot(circle[:, 0], circle[:, 1] - 1.0), 1.0, atol=1e-9)
    np.testing.assert_allclose(circle[-1, :2], [0.0, 0.0], atol=1e-9)


def test_first_collision_names_the_first_pose_whose_footprint_touches_lethal_or_off_map() -> None:
    grid = np.zeros((40, 40), np.uint8)
    grid[:, 30] = Costmap.LETHAL  # a wall at x = 1.50 .. 1.55 m
    behavior = attached(grid)
    poses = np.array([[0.5, 1.0, 0.0], [1.0, 1.0, 0.0], [1.3, 1.0, 0.0], [1.0, 1.0, 0.0]])
    assert behavior.first_collision(poses) == 2  # its front edge at 1.50 m
    assert behavior.is_collision_free(poses[:2])
    assert not behavior.is_collision_free([0.1, 1.0, 0.0])  # the footprint leaves the map
    grid[:, 30] = Costmap.INSCRIBED  # inscribed is not a collision (Nav2's isCollisionFree)
    assert attached(grid).is_collision_free(poses)


def test_command_numbers_are_floats_and_refuse_non_numbers() -> None:
    command = Command("nav2_msgs/action/BackUp", {"target_x": -1, "label": "x", "flag": True})
    assert command.number("target_x") == -1.0 and isinstance(command.number("target_x"), float)
    assert command.number("speed", 0.1) == 0.1
    assert command.action == "nav2_msgs/action/BackUp" and dict(command)["label"] == "x"
    for name in ("label", "flag"):
        with pytest.raises(TypeError, match=f"goal field '{name}'"):
            command.number(name)


def test_freest_backup_prefers_straight_back_then_the_freest_smallest_turn() -> None:
    open_room = np.zeros((80, 80), np.uint8)
    assert attached(open_room).choose(2.0, 2.0, 0.0, 0.3, 0.15) == (0.0, -0.15)
    walled = open_room.copy()
    walled[:, 32:34] = Costmap.LETHAL  # behind the robot
    walled[45:, :] = Costmap.LETHAL  # and everything above y = 2.25 m
    face, speed = attached(walled).choose(2.0, 2.0, 0.0, 0.3, 0.15)
    heading = face if speed > 0 else face + math.pi
    # the motion goes away from both walls: +x, or down (-y), never up or back
    assert math.cos(heading) > -0.1 and math.sin(heading) < 0.1
    boxed = np.full((80, 80), Costmap.LETHAL, np.uint8)
    boxed[36:44, 34:46] = 0
    assert attached(boxed).choose(2.0, 2.0, 0.0, 0.3, 0.15) is None
