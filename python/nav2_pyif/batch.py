"""Batched control cycles: one call of a controller class for the cycles of many robots.

A Controller subclass says it can batch by defining the classmethod
``compute_velocity_commands_batch``. A planner host run with ``--batch`` then serves all the
keys of that planner from one worker process, gathers the ``compute_velocity_commands`` calls
that arrive within the batch window (``--batch-window``) and makes one call for them::

    import numpy as np
    from nav2_pyif import Batch, Controller, one_cycle

    class GoStraight(Controller):
        def configure(self) -> None:
            self.speed = self.params.declare("speed", 0.3, "forward speed [m/s]")

        def compute_velocity_commands(self, pose, velocity, goal_checker):
            return one_cycle(self, pose, velocity, goal_checker)  # a batch of one

        @classmethod
        def compute_velocity_commands_batch(cls, batch: Batch) -> np.ndarray:
            speeds = np.array([robot.speed for robot in batch.planners])
            return np.column_stack([speeds, np.zeros(len(batch)), np.zeros(len(batch))])

Each robot keeps its own planner instance (``batch.planners[i]``): its plan, costmap,
parameters, inputs and speed limit, configured, restored after a worker restart and handed
over on a hot swap exactly as without batching. The single-robot
``compute_velocity_commands`` is still required: the host calls it where nothing is batched
(``planner-host`` without ``--batch``, the offline runner's own host).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Union

import numpy as np

from nav2_pyif.geometry import pose_xy_yaw
from nav2_pyif.goal_tolerances import GoalTolerances

if TYPE_CHECKING:
    from nav2_pyif.controller import Controller

#: What ``compute_velocity_commands_batch`` returns: an (N, 3) array of vx, vy [m/s], wz
#: [rad/s] (one row per robot, in the robot's base frame), or N items each a TwistStamped, a
#: (vx, vy, wz) triple, or an exception: that robot's own error (a NoValidControl, ...). A
#: row with a NaN or an infinity fails that robot alone, with NoValidControl.
BatchResult = Union[np.ndarray, Sequence[Any]]  # noqa: UP007 (a runtime alias: Python 3.10)


@dataclass
class Batch:
    """The control cycles of N robots, in the order their calls arrived."""

    planners: list[Controller]  # each robot's own planner instance (its session's state)
    poses: np.ndarray  # (N, 3) float64: x, y [m], yaw [rad], in each robot's global frame
    velocities: np.ndarray  # (N, 3) float64: vx, vy [m/s], wz [rad/s], robot base frame
    goal_checkers: list[GoalTolerances | None]  # each robot's goal checker tolerances, or None
    pose_messages: list[Any]  # geometry_msgs/PoseStamped per robot, as the single call gets
    velocity_messages: list[Any]  # geometry_msgs/Twist per robot

    def __len__(self) -> int:
        return len(self.planners)

    def take(self, indices: Sequence[int]) -> Batch:
        """The robots at ``indices``, in that order (e.g. those a planner optimises)."""
        rows = np.asarray(indices, dtype=int)
        return Batch(
            [self.planners[i] for i in rows],
            self.poses[rows],
            self.velocities[rows],
            [self.goal_checkers[i] for i in rows],
            [self.pose_messages[i] for i in rows],
            [self.velocity_messages[i] for i in rows],
        )

    @classmethod
    def of(
        cls,
        planners: Sequence[Controller],
        poses: Sequence[Any],
        velocities: Sequence[Any],
        goal_checkers: Sequence[GoalTolerances | None],
    ) -> Batch:
        """A batch from the messages of the single call (PoseStamped, Twist) per robot."""
        return cls(
            list(planners),
            np.array([pose_xy_yaw(p) for p in poses], dtype=np.float64).reshape(-1, 3),
            np.array(
                [(v.linear.x, v.linear.y, v.angular.z) for v in velocities], dtype=np.float64
            ).reshape(-1, 3),
            list(goal_checkers),
            list(poses),
            list(velocities),
        )

    @classmethod
    def of_one(
        cls,
        planner: Controller,
        pose: Any,
        velocity: Any,
        goal_checker: GoalTolerances | None = None,
    ) -> Batch:
        """One robot's cycle as a batch of one: the single call written on the batched one."""
        return cls.of([planner], [pose], [velocity], [goal_checker])


def can_batch(planner_class: type) -> bool:
    """Whether ``planner_class`` defines ``compute_velocity_commands_batch``."""
    return callable(getattr(planner_class, "compute_velocity_commands_batch", None))


def bucket(n: int) -> int:
    """A padded batch size for jit-compiled code (static shapes): 1, 2, 4, 8, then multiples
    of 4, so a fleet of N robots compiles about N / 4 shapes, never one per N, and computes
    at most 3 padding rows above 8."""
    if n <= 8:
        return 1 << max(0, (n - 1).bit_length())
    return -(-n // 4) * 4


def buckets(up_to: int) -> list[int]:
    """Every size ``bucket`` gives for 1..``up_to`` robots: the shapes to compile ahead."""
    return sorted({bucket(n) for n in range(1, max(1, up_to) + 1)})


def pad_rows(array: np.ndarray, size: int) -> np.ndarray:
    """``array`` (N, ...) padded to ``size`` rows by repeating its last row (results for the
    padding are dropped; repeating a real row keeps every value finite)."""
    missing = size - len(array)
    if missing <= 0:
        return array
    return np.concatenate([array, np.repeat(array[-1:], missing, axis=0)])


def as_twist_stamped(item: Any, pose: Any, base_frame: str) -> Any:
    """One robot's item of a BatchResult as the TwistStamped its single call would return
    (stamped with its pose's stamp, in its base frame); an exception item is raised."""
    from geometry_msgs.msg import TwistStamped

    if isinstance(item, BaseException):
        raise item
    if isinstance(item, TwistStamped):
        return item
    vx, vy, wz = (float(v) for v in np.asarray(item, dtype=np.float64).reshape(3))
    cmd = TwistStamped()
    cmd.header.stamp = pose.header.stamp
    cmd.header.frame_id = base_frame
    cmd.twist.linear.x, cmd.twist.linear.y, cmd.twist.angular.z = vx, vy, wz
    return cmd


def items(result: BatchResult, n: int) -> list[Any]:
    """A BatchResult as its N per-robot items; a ValueError when it does not hold N."""
    if isinstance(result, np.ndarray):
        if result.ndim != 2 or result.shape != (n, 3):
            raise ValueError(
                f"compute_velocity_commands_batch returned an array of shape {result.shape}; "
                f"expected ({n}, 3): vx, vy, wz per robot"
            )
        return list(result)
    listed = list(result)
    if len(listed) != n:
        raise ValueError(
            f"compute_velocity_commands_batch returned {len(listed)} items for {n} robots"
        )
    return listed


def one_cycle(
    planner: Controller, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
) -> Any:
    """The single-robot ``compute_velocity_commands`` of a batching controller: its
    ``compute_velocity_commands_batch`` on a batch of one, the result as a TwistStamped."""
    batched = type(planner).compute_velocity_commands_batch  # type: ignore[attr-defined]
    result = batched(Batch.of_one(planner, pose, velocity, goal_checker))
    return as_twist_stamped(items(result, 1)[0], pose, planner.robot_base_frame)
