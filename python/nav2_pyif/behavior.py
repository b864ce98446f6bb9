"""Base class of Python behaviours: mirrors nav2_behaviors::TimedBehavior (behavior_server's
Spin, BackUp, DriveOnHeading, Wait), as nav2_core::Behavior plugins run them.

Nav2 calls ``on_run(command)`` once when the action's goal arrives, then, while it answers
RUNNING, ``on_cycle_update(pose, elapsed)`` every 1 / cycle_frequency seconds, publishing the
command each step returns; ``on_action_completion`` when the action ends.
"""

from __future__ import annotations

import math
from abc import abstractmethod
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from nav2_pyif_protocol.constants import BehaviorFailure, BehaviorStatus, PluginType

from nav2_pyif.params import ParamValue
from nav2_pyif.plugin import PlannerPlugin

FloatArray = npt.NDArray[np.float64]


# TimedBehavior's Status and why a behaviour failed: the protocol's names (constants.py).
Status = BehaviorStatus
Failure = BehaviorFailure


@dataclass
class Step:
    """One ``on_cycle_update`` answer: TimedBehavior's ResultStatus plus the command to
    publish this cycle (None: publish nothing; the plugin stops the robot when the status is
    not RUNNING) and the action's feedback fields (e.g. ``distance_traveled``)."""

    status: Status
    cmd_vel: Any = None  # geometry_msgs/TwistStamped
    failure: Failure = Failure.NONE
    feedback: dict[str, ParamValue] = field(default_factory=dict)

    @classmethod
    def running(cls, cmd_vel: Any, **feedback: ParamValue) -> Step:
        return cls(Status.RUNNING, cmd_vel, Failure.NONE, dict(feedback))

    @classmethod
    def succeeded(cls, **feedback: ParamValue) -> Step:
        return cls(Status.SUCCEEDED, None, Failure.NONE, dict(feedback))

    @classmethod
    def failed(cls, failure: Failure | str = Failure.UNKNOWN, **feedback: ParamValue) -> Step:
        return cls(Status.FAILED, None, Failure(failure), dict(feedback))


class Command(Mapping[str, ParamValue]):
    """The action's goal: its fields as plain values (PROTOCOL.md section 17), e.g. BackUp's
    ``target_x`` [m], ``speed`` [m/s], ``time_allowance`` [s], ``disable_collision_checks``;
    Spin's ``target_yaw`` [rad]. ``action`` names the action type."""

    def __init__(self, action: str, fields: Mapping[str, ParamValue]) -> None:
        self.action = action
        self._fields = dict(fields)

    def __getitem__(self, name: str) -> ParamValue:
        return self._fields[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._fields)

    def __len__(self) -> int:
        return len(self._fields)

    def number(self, name: str, default: float = 0.0) -> float:
        """A numeric field as a float (``default`` when the goal has no such field)."""
        value = self._fields.get(name, default)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise TypeError(f"goal field {name!r} is {value!r}, not a number")
        return float(value)

    def __repr__(self) -> str:
        return f"Command({self.action!r}, {self._fields!r})"


def arc(
    x: float, y: float, yaw: float, vx: float, wz: float, duration: float, dt: float
) -> FloatArray:
    """Poses (N, 3) — x, y [m], yaw [rad] — of a robot driving ``vx`` [m/s], ``wz`` [rad/s]
    from (x, y, yaw), every ``dt`` [s] from ``dt`` on, the last one at ``duration`` [s]
    (DriveOnHeading's simulate-ahead; exact for arcs)."""
    n = max(1, math.ceil(duration / dt - 1e-9))
    t = np.minimum(np.arange(1, n + 1) * dt, max(duration, dt))
    heading = yaw + wz * t
    if abs(wz) < 1e-9:
        xs, ys = x + vx * t * math.cos(yaw), y + vx * t * math.sin(yaw)
    else:
        r = vx / wz
        xs = x + r * (np.sin(heading) - math.sin(yaw))
        ys = y - r * (np.cos(heading) - math.cos(yaw))
    return np.stack([np.broadcast_to(xs, t.shape), np.broadcast_to(ys, t.shape), heading], axis=1)


class Behavior(PlannerPlugin):
    """Subclass and implement ``on_cycle_update`` (and usually ``on_run``)::

        import math

        from geometry_msgs.msg import TwistStamped
        from nav2_pyif import Behavior, Status, Step, arc, pose_xy_yaw

        class Creep(Behavior):
            def on_run(self, command):
                self.start, self.distance = pose_xy_yaw(self.pose), abs(command["target_x"])
                return Status.SUCCEEDED

            def on_cycle_update(self, pose, elapsed):
                x, y, yaw = pose_xy_yaw(pose)
                if math.hypot(x - self.start[0], y - self.start[1]) >= self.distance:
                    return Step.succeeded()
                if not self.is_collision_free(arc(x, y, yaw, -0.1, 0.0, 1.0, 0.1)):
                    return Step.failed("collision_ahead")
                cmd = TwistStamped(header=pose.header)
                cmd.twist.linear.x = -0.1
                return Step.running(cmd)

    ``self.costmap`` is behavior_server's local costmap with its footprint (the last one
    Nav2 received; 0 x 0 before), in ``self.global_frame`` (behavior_server's local_frame),
    the frame of every pose given. ``self.pose`` is the robot pose of the latest call.
    """

    plugin_type: ClassVar[PluginType] = PluginType.BEHAVIOR
    pose: Any = None  # geometry_msgs/PoseStamped, set before each on_run / on_cycle_update

    def on_run(self, command: Command) -> Any:
        """The action's goal arrived. Return Status.SUCCEEDED to start cycling, or
        Status.FAILED / ``(Status.FAILED, Failure.INVALID_INPUT)`` / ``Step.failed(...)`` to
        end the action at once (TimedBehavior's onRun)."""
        return Status.SUCCEEDED

    @abstractmethod
    def on_cycle_update(self, pose: Any, elapsed: float) -> Any:
        """One cycle: ``pose`` (geometry_msgs/PoseStamped, ``self.global_frame``), ``elapsed``
        seconds since on_run. Return a Step, a Status, or ``(Status, TwistStamped | None)``.
        A raised exception ends the action as FAILED (UNKNOWN), its traceback in the logs."""

    def on_action_completion(self, status: str, elapsed: float) -> None:
        """The action ended: ``status`` 'succeeded', 'failed' or 'cancelled' after ``elapsed``
        seconds (TimedBehavior's onActionCompletion)."""

    # --- collision checks (CostmapTopicCollisionChecker's, vectorised) -------------------
    def footprint_costs(self, poses: npt.ArrayLike) -> npt.NDArray[np.uint8]:
        """Max cost under the footprint at each pose: (..., 3) x, y, yaw -> (...,) uint8;
        cells off the costmap count as NO_INFORMATION."""
        return self.costmap.footprint_costs(poses)

    def first_collision(self, poses: npt.ArrayLike) -> int | None:
        """Index of the first pose of (N, 3) whose footprint touches a lethal, unknown or
        off-map cell (Nav2's isCollisionFree false), None when every pose is free."""
        hit = np.flatnonzero(self.footprint_costs(np.atleast_2d(poses)) >= self.costmap.LETHAL)
        return int(hit[0]) if len(hit) else None

    def is_collision_free(self, poses: npt.ArrayLike) -> bool:
        """Whether every pose of (N, 3) (or one (3,) pose) is free for the footprint."""
        return self.first_collision(poses) is None
