"""The runner's recovery, as Nav2's behaviour tree makes one: when the controller keeps failing
past its failure tolerance, behavior_server's BackUp runs (here a Python behaviour served by the
planner host: ``--recovery``, e.g. free_backup), cycle by cycle on the simulated robot, and then
the controller follows the plan again (a new FollowPath goal: the checkers reset). The run ends
only when the recoveries are spent (``--max-recoveries``) or one fails."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from nav2_pyif.behavior import Status
from nav2_pyif.client.behavior import BehaviorClient

BACKUP = "nav2_msgs/action/BackUp"
#: The BackUp goal of Nav2's default navigate_to_pose tree (backup_dist 0.30, backup_speed 0.15).
BACKUP_COMMAND = {
    "target_x": -0.3,
    "target_y": 0.0,
    "target_z": 0.0,
    "speed": 0.15,
    "time_allowance": 10.0,
    "disable_collision_checks": False,
}


@dataclass
class Recovery:
    """One recovery the run made: when, for how long, and how it ended."""

    sim_time: float  # [s] when it began
    seconds: float  # [s] of simulated time it took
    outcome: str  # "succeeded", or why it failed


def back_up(
    behavior: BehaviorClient,
    pose_now: Callable[[], Any],
    drive: Callable[[float, float], bool],
    dt: float,
    sim_time: float,
) -> Recovery:
    """BackUp at the robot's pose (``pose_now``: a PoseStamped), driving the robot by each
    cycle's command for ``dt`` (``drive(v, w)``: False once it collided), as TimedBehavior does:
    on_run, on_cycle_update while RUNNING, on_action_completion."""
    status, failure = behavior.run(BACKUP, BACKUP_COMMAND, pose_now())
    if status is not Status.SUCCEEDED:
        behavior.action_completion("failed", 0.0)
        return Recovery(sim_time, 0.0, f"refused ({failure.value})")
    elapsed = 0.0
    time_allowance = float(BACKUP_COMMAND["time_allowance"])
    while elapsed <= time_allowance:
        step = behavior.cycle_update(pose_now(), elapsed)
        if step.status is not Status.RUNNING:
            behavior.action_completion(step.status.value, elapsed)
            ended = "succeeded" if step.status is Status.SUCCEEDED else step.failure.value
            return Recovery(sim_time, elapsed, ended)
        twist = step.cmd_vel.twist if step.cmd_vel is not None else None
        moving = (twist.linear.x, twist.angular.z) if twist is not None else (0.0, 0.0)
        if not drive(*moving):
            behavior.action_completion("failed", elapsed)
            return Recovery(sim_time, elapsed, "collision")
        elapsed += dt
    behavior.action_completion("failed", elapsed)
    return Recovery(sim_time, elapsed, f"timed out after {time_allowance:g} s")
