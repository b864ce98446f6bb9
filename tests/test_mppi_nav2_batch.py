"""Nav2MPPI batched (fleet.py): robots served in one host call get the commands their
own single cycles give, keep their own warm starts, and a robot's own error (no plan, every
rollout colliding) is its item alone."""

from __future__ import annotations

import math

import numpy as np
import pytest
from geometry_msgs.msg import Twist, TwistStamped
from nav2_pyif import Batch, Costmap, Inflation, NoValidControl
from nav2_pyif.runner.run import pose_msg

pytestmark = pytest.mark.unit

pytest.importorskip("jax", reason="JAX is not installed (nav2-pyif-planners[jax])")

from nav2_pyif_planners.mppi_nav2 import Nav2MPPI  # noqa: E402

from tests.test_mppi_nav2 import FREE, RECTANGLE, controller, line  # noqa: E402

STARTS = [(0.5, 2.0, 0.0), (1.0, 2.1, 0.2), (1.5, 1.9, -0.2)]


def test_batched_commands_are_each_robots_own_cycle() -> None:
    alone = [controller() for _ in STARTS]
    together = [controller() for _ in STARTS]  # the padded size of 3 compiled at first call
    for robot in (*alone, *together):
        robot.set_plan(line(0.5, 5.5))
    poses = list(STARTS)
    velocities = [Twist() for _ in STARTS]
    for _ in range(8):  # the warm starts carried over cycles, each robot its own
        single = [
            r.compute_velocity_commands(pose_msg(*p), v, None)
            for r, p, v in zip(alone, poses, velocities, strict=True)
        ]
        batch = Batch.of(together, [pose_msg(*p) for p in poses], velocities, [None] * 3)
        batched = Nav2MPPI.compute_velocity_commands_batch(batch)
        for a, b in zip(single, batched, strict=True):
            assert isinstance(b, TwistStamped) and b.header.frame_id == "base_link"
            assert b.twist.linear.x == pytest.approx(a.twist.linear.x, abs=1e-3)
            assert b.twist.angular.z == pytest.approx(a.twist.angular.z, abs=1e-3)
        poses = [advance(p, cmd) for p, cmd in zip(poses, batched, strict=True)]
        velocities = [cmd.twist for cmd in batched]
    assert min(v.linear.x for v in velocities) > 0.1  # all three under way, not stuck


def advance(pose: tuple[float, float, float], cmd: TwistStamped) -> tuple[float, float, float]:
    x, y, yaw = pose
    yaw += cmd.twist.angular.z * 0.05
    vx = cmd.twist.linear.x
    return x + vx * math.cos(yaw) * 0.05, y + vx * math.sin(yaw) * 0.05, yaw


def test_a_robots_own_error_is_its_item_and_the_others_are_served() -> None:
    costs = FREE.copy()
    costs[30:50, 5:40] = Costmap.LETHAL  # walls all round the robot at (1, 2)
    walled = Costmap(costs, 0.05, footprint=RECTANGLE, inflation=Inflation(0.55, 3.0))
    served, planless, boxed = controller(), controller(), controller(walled)
    served.set_plan(line(0.5, 5.5))
    boxed.set_plan(line(0.5, 3.0))
    robots = [served, planless, boxed]
    poses = [pose_msg(0.5, 2.0, 0.0), pose_msg(0.5, 2.0, 0.0), pose_msg(1.0, 2.0, 0.0)]
    out = Nav2MPPI.compute_velocity_commands_batch(
        Batch.of(robots, poses, [Twist()] * 3, [None] * 3)
    )
    assert isinstance(out[0], TwistStamped) and np.isfinite(out[0].twist.linear.x)
    assert isinstance(out[1], NoValidControl) and "no plan" in str(out[1])
    assert isinstance(out[2], NoValidControl) and "Optimizer fail" in str(out[2])
