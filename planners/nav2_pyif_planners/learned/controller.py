"""The learned policy served as a Nav2 controller: features from input "scan", the plan and
the velocity; inference with JAX on its default device (a GPU where one is present), one jit
compiled function over a batch dimension.

Batched (``planner-host --batch``): the features of every robot in a batch stacked, one
forward pass per policy (robots with another ``weights`` parameter get their own), the
batch padded to ``nav2_pyif.batch.bucket`` sizes compiled in ``configure`` up to the
``fleet_size`` parameter. Sessions of one weights file share its device copy and compiled
function.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from nav2_pyif import Batch, GoalTolerances, NoValidControl, one_cycle
from nav2_pyif.batch import bucket, buckets, pad_rows
from nav2_pyif.geometry import limit_speed

from nav2_pyif_planners.follower import PathFollower
from nav2_pyif_planners.learned.features import features_of, plan_window
from nav2_pyif_planners.learned.policy import Policy, default_weights, forward, import_jax


@dataclass
class _Served:
    """A policy on the device: its weights, compiled forward pass and the device."""

    policy: Policy
    infer: Callable[[Any], Any]
    device: str


@dataclass
class _Observed:
    """What the policy sees of one robot, before its features are stacked with the batch's."""

    scan: tuple[np.ndarray, np.ndarray]  # ranges, angles
    window: np.ndarray  # (PLAN_POINTS, 2) the plan ahead in the robot frame
    velocity: Any  # geometry_msgs/Twist


#: (weights path, modification time) -> the policy served from it, shared by its sessions
_SERVED: dict[tuple[str, float], _Served] = {}


def _served(path: Path) -> _Served:
    key = (str(path), path.stat().st_mtime)
    if key not in _SERVED:
        jax = import_jax()
        policy = Policy.load(path)
        device = jax.devices()[0]  # a GPU when JAX has one, else the CPU
        if device.platform == "cpu":
            # Each result is waited for at once (the commands go back in this cycle), so on a
            # CPU asynchronous dispatch only adds a hand-off to XLA's thread: 28 against 67 us
            # a batch of 32 on a loaded 2-core machine. A GPU keeps it.
            jax.config.update("jax_cpu_enable_async_dispatch", False)
        params = [(jax.device_put(w, device), jax.device_put(b, device)) for w, b in policy.layers]
        _SERVED[key] = _Served(policy, jax.jit(lambda x: forward(params, x)), str(device))
    return _SERVED[key]


class LearnedController(PathFollower):
    """Needs input "scan" (sensor_msgs/LaserScan): in Nav2, the plugin's ``inputs``
    parameter; offline, ``nav2-pyif sim --scan``. Parameter ``weights``: the .npz written by
    ``nav2-pyif learn`` (default: the user's data directory); ``fleet_size``: the most
    robots a batched host serves with it (their batch shapes are compiled in configure)."""

    def configure(self) -> None:
        p = self.params
        path = Path(str(p.declare("weights", str(default_weights()), "policy .npz")))
        if not path.is_file():
            raise FileNotFoundError(f"no policy weights at {path}: run nav2-pyif learn first")
        self.xy_goal_tolerance = p.declare("xy_goal_tolerance", 0.25, "[m] when no goal checker")
        fleet = p.declare("fleet_size", 1, "robots a batched host serves at most")
        self.index = 0
        served = _served(path)
        self.policy, self._infer, self.device = served.policy, served.infer, served.device
        self.weights = str(path)
        for size in buckets(int(fleet)):  # compile now; cached per shape after the first
            self._infer(np.zeros((size, len(self.policy.mean)), np.float32))
        self.logger.info("policy %s on %s", path, self.device)

    def act(self, batch: np.ndarray) -> np.ndarray:
        """(B, F) features -> (B, 2) v [m/s], w [rad/s]: one call for a whole batch, padded
        to a compiled size."""
        x = (batch - self.policy.mean) / self.policy.std
        padded = pad_rows(x.astype(np.float32), bucket(len(x)))
        out: np.ndarray = np.asarray(self._infer(padded))[: len(x)] * self.policy.scale
        return out

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        return one_cycle(self, pose, velocity, goal_checker)

    def _observe(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> tuple[Any, _Observed | None]:
        """This robot's command, and what the policy needs to fill it in: None when it is at
        the goal (the command then turns it in place)."""
        x, y, yaw, path = self.track(pose)
        cmd = self.command(pose)
        if self.turn_at_goal(cmd, x, y, yaw, path, goal_checker):
            return cmd, None
        scan = self.inputs.get("scan")
        if scan is None:
            raise NoValidControl("no laser scan yet: the policy needs input 'scan'")
        along = self.plan.along if self.plan is not None else None
        window = plan_window(path[:, :2], self.index, x, y, yaw, along)
        return cmd, _Observed((scan.ranges, scan.angles), window, velocity)

    @classmethod
    def compute_velocity_commands_batch(cls, batch: Batch) -> list[Any]:
        """Each robot's features (their scans pooled together), then one forward pass per
        policy for all of them."""
        out: list[Any] = [None] * len(batch)
        observed: list[tuple[int, LearnedController, Any, _Observed]] = []
        for i, robot in enumerate(batch.planners):
            assert isinstance(robot, LearnedController)
            args = batch.pose_messages[i], batch.velocity_messages[i], batch.goal_checkers[i]
            try:
                cmd, seen = robot._observe(*args)
            except Exception as exc:  # this robot's own error (no scan, no plan)
                out[i] = exc
                continue
            if seen is None:
                out[i] = cmd
            else:
                observed.append((i, robot, cmd, seen))
        if not observed:
            return out
        rows = features_of(
            [seen.scan for *_, seen in observed],
            np.stack([seen.window for *_, seen in observed]),
            np.array([(s.velocity.linear.x, s.velocity.angular.z) for *_, s in observed]),
        )
        by_policy: dict[str, list[int]] = {}
        for n, (_, robot, _, _) in enumerate(observed):
            by_policy.setdefault(robot.weights, []).append(n)
        for group in by_policy.values():
            commands = observed[group[0]][1].act(rows[group])
            for n, (v, w) in zip(group, commands, strict=True):
                i, robot, cmd, _ = observed[n]
                top = limit_speed(float(robot.policy.scale[0]), robot.speed_limit)
                cmd.twist.linear.x = float(min(max(v, 0.0), top))
                cmd.twist.angular.z = float(w)
                out[i] = cmd
        return out
