"""A BackUp that goes where there is room: behavior_server's ``backup`` (nav2_msgs/action/BackUp,
the recovery Nav2's default behaviour trees call) served from Python::

    planner-host --key nav2_pyif/robot1/backup \\
        --planner nav2_pyif_planners.free_backup:FreestBackUp

Nav2's BackUp drives straight backwards and fails when the costmap is occupied behind the
robot, which is where a robot stuck against a wall often is. This one backs up when the
footprint has ``target_x`` of free space straight behind; otherwise it scores every heading
(``headings`` of them) by the free distance the footprint can travel along it on the local
costmap, turns in place (footprint checked through the whole turn) towards the freest one —
forwards or backwards, whichever needs the smaller turn — and drives the distance there.
Each cycle checks the motion of the next ``simulate_ahead_time`` seconds, as DriveOnHeading
does, and fails with COLLISION_AHEAD rather than drive into anything.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Behavior, Command, Failure, Status, Step, arc, pose_xy_yaw


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))


class FreestBackUp(Behavior):
    """Back up ``target_x`` metres, or turn towards the freest heading and go there."""

    def configure(self) -> None:
        p = self.params
        self.headings = p.declare("headings", 16, "headings scored around the robot")
        self.rotational_speed = p.declare("rotational_speed", 0.6, "turn rate [rad/s]")
        self.yaw_tolerance = p.declare("yaw_tolerance", 0.05, "turned once within [rad]")
        self.simulate_ahead_time = p.declare(
            "simulate_ahead_time", 2.0, "motion checked ahead each cycle [s]"
        )
        self.cycle_dt = p.declare("cycle_dt", 0.1, "collision-check step along a motion [s]")
        self.plan: tuple[float, float] | None = None  # (yaw to face, signed speed)

    # --- planning ------------------------------------------------------------------------
    def free_distance(self, x: float, y: float, yaw: float, heading: float, reach: float) -> float:
        """How far [m] the footprint, kept at ``yaw``, travels from (x, y) along ``heading``
        before touching a lethal or unknown cell (``reach`` at most)."""
        step = max(self.costmap.resolution, 1e-3)
        s = np.arange(1, math.ceil(reach / step) + 1) * step
        poses = np.stack(
            [x + s * math.cos(heading), y + s * math.sin(heading), np.full_like(s, yaw)], axis=1
        )
        hit = self.first_collision(poses)
        return float(reach if hit is None else (s[hit - 1] if hit > 0 else 0.0))

    def turn_is_free(self, x: float, y: float, yaw: float, target: float) -> bool:
        """Whether the footprint may turn in place from ``yaw`` to ``target``."""
        delta = _wrap(target - yaw)
        n = max(2, math.ceil(abs(delta) / 0.05))
        yaws = yaw + np.linspace(0.0, delta, n)
        return self.is_collision_free(np.stack([np.full(n, x), np.full(n, y), yaws], axis=1))

    def choose(self, x: float, y: float, yaw: float, distance: float, speed: float) -> Any:
        """(yaw to face, signed speed), or None when no heading has room."""
        reach = distance * 1.5  # room to stop beyond the target
        if self.free_distance(x, y, yaw, yaw + math.pi, reach) >= reach:
            return yaw, -speed  # Nav2's BackUp: straight backwards
        best: tuple[tuple[float, float], float, float] | None = None  # key, face, sign
        for heading in yaw + np.arange(1, self.headings) * (2.0 * math.pi / self.headings):
            # drive forwards facing the heading, or backwards facing away from it
            forward = abs(_wrap(heading - yaw)) <= abs(_wrap(heading + math.pi - yaw))
            face, sign = (heading, 1.0) if forward else (heading + math.pi, -1.0)
            if not self.turn_is_free(x, y, yaw, face):
                continue
            free = self.free_distance(x, y, face, heading, reach)
            key = (free, -abs(_wrap(face - yaw)))  # the freest, then the smallest turn
            if free >= distance and (best is None or key > best[0]):
                best = (key, _wrap(face), sign)
        return None if best is None else (best[1], best[2] * speed)

    # --- TimedBehavior's hooks -----------------------------------------------------------
    def on_run(self, command: Command) -> Any:
        if command.number("target_y") or command.number("target_z"):
            self.logger.info("Backing up in Y and Z not supported, will only move in X.")
            return Status.FAILED, Failure.INVALID_INPUT
        self.distance = abs(command.number("target_x", 0.3))
        self.speed = abs(command.number("speed", 0.1)) or 0.1
        self.time_allowance = command.number("time_allowance", 10.0)
        self.check = not bool(command.get("disable_collision_checks", False))
        self.start = pose_xy_yaw(self.pose)
        x, y, yaw = self.start
        if not self.check:
            self.plan = (yaw, -self.speed)
        else:
            self.plan = self.choose(x, y, yaw, self.distance, self.speed)
        if self.plan is None:
            self.logger.warning("no heading has %.2f m of free space", self.distance)
            return Status.FAILED, Failure.COLLISION_AHEAD
        self.turned = abs(_wrap(self.plan[0] - yaw)) <= self.yaw_tolerance
        self.drive_start = self.start
        self.logger.info(
            "%s: face %.2f rad (a %.2f rad turn), then drive %.2f m at %.2f m/s",
            self.name,
            self.plan[0],
            _wrap(self.plan[0] - yaw),
            self.distance,
            self.plan[1],
        )
        return Status.SUCCEEDED

    def on_cycle_update(self, pose: Any, elapsed: float) -> Any:
        assert self.plan is not None
        if self.time_allowance > 0.0 and elapsed > self.time_allowance:
            self.logger.warning("time allowance exceeded")
            return Step.failed(Failure.TIMEOUT)
        x, y, yaw = pose_xy_yaw(pose)
        face, speed = self.plan
        cmd = TwistStamped(header=pose.header)
        cmd.header.frame_id = self.robot_base_frame
        if not self.turned:
            error = _wrap(face - yaw)
            if abs(error) <= self.yaw_tolerance:
                self.turned = True
                self.drive_start = (x, y, yaw)
            else:
                wz = math.copysign(min(self.rotational_speed, 2.0 * abs(error)), error)
                if self.check and not self.turn_is_free(x, y, yaw, face):
                    return Step.failed(Failure.COLLISION_AHEAD)
                cmd.twist.angular.z = wz
                return Step.running(cmd, distance_traveled=0.0)
        travelled = math.hypot(x - self.drive_start[0], y - self.drive_start[1])
        if travelled >= self.distance:
            return Step.succeeded(distance_traveled=travelled)
        if self.check:
            remaining = self.distance - travelled
            ahead = arc(
                x, y, yaw, speed, 0.0, min(self.simulate_ahead_time, remaining / abs(speed)),
                self.cycle_dt,
            )  # fmt: skip
            if not self.is_collision_free(ahead):
                self.logger.warning("collision ahead after %.2f m", travelled)
                return Step.failed(Failure.COLLISION_AHEAD, distance_traveled=travelled)
        cmd.twist.linear.x = speed
        return Step.running(cmd, distance_traveled=travelled)

    def on_action_completion(self, status: str, elapsed: float) -> None:
        self.plan = None
