"""The batched API planner authors use (nav2_pyif.batch), without a host: a batch of one for
the single call, padded sizes for jit-compiled code, and what a batched method may return."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped, Twist, TwistStamped
from nav2_pyif import Batch, Controller, NoValidControl, one_cycle
from nav2_pyif.batch import as_twist_stamped, bucket, buckets, can_batch, items, pad_rows

from tests.conftest import make_costmap
from tests.test_planners import attach

pytestmark = pytest.mark.unit


class Rows(Controller):
    """vx = pose x, vy = 0, wz = index in the batch."""

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        return one_cycle(self, pose, velocity, goal_checker)

    @classmethod
    def compute_velocity_commands_batch(cls, batch: Batch) -> np.ndarray:
        return np.column_stack([batch.poses[:, 0], np.zeros(len(batch)), np.arange(len(batch))])


def pose_at(x: float) -> Any:
    pose = PoseStamped()
    pose.header.frame_id = "odom"
    pose.header.stamp.sec = 7
    pose.pose.position.x = x
    pose.pose.orientation.w = 1.0
    return pose


def test_the_single_call_is_a_batch_of_one() -> None:
    robot = attach(Rows(), make_costmap())
    cmd = robot.compute_velocity_commands(pose_at(2.5), Twist(), None)
    assert isinstance(cmd, TwistStamped)
    assert (cmd.twist.linear.x, cmd.twist.angular.z) == (2.5, 0.0)
    assert cmd.header.frame_id == "base_link" and cmd.header.stamp.sec == 7
    assert can_batch(Rows) and not can_batch(Controller)


def test_a_batch_keeps_each_robots_planner_and_rows_in_order() -> None:
    robots = [attach(Rows(), make_costmap()) for _ in range(3)]
    batch = Batch.of(robots, [pose_at(x) for x in (1.0, 2.0, 3.0)], [Twist()] * 3, [None] * 3)
    assert batch.poses.shape == (3, 3) and batch.velocities.shape == (3, 3)
    sub = batch.take([2, 0])
    assert sub.planners == [robots[2], robots[0]] and list(sub.poses[:, 0]) == [3.0, 1.0]


def test_what_a_batched_method_may_return() -> None:
    with pytest.raises(ValueError, match=r"shape \(2, 2\); expected \(3, 3\)"):
        items(np.zeros((2, 2)), 3)
    with pytest.raises(ValueError, match="returned 2 items for 3 robots"):
        items([(0, 0, 0)] * 2, 3)
    with pytest.raises(NoValidControl, match="its own"):
        as_twist_stamped(NoValidControl("its own"), pose_at(0), "base_link")
    nan = as_twist_stamped((math.nan, 0, 0), pose_at(0), "base_link")
    assert math.isnan(nan.twist.linear.x)  # the host refuses it for that robot alone


def test_padded_sizes_are_few_and_never_smaller() -> None:
    assert [bucket(n) for n in (1, 2, 3, 5, 8, 9, 12, 13, 40, 41)] == [
        1, 2, 4, 8, 8, 12, 12, 16, 40, 44,
    ]  # fmt: skip
    assert buckets(20) == [1, 2, 4, 8, 12, 16, 20]
    padded = pad_rows(np.arange(6.0).reshape(3, 2), 4)
    assert padded.shape == (4, 2) and (padded[3] == padded[2]).all()
