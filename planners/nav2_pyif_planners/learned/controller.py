"""The learned policy served as a Nav2 controller: features from input "scan", the plan and
the velocity; inference with JAX on its default device (a GPU where one is present), one jit
compiled function over a batch dimension."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from nav2_pyif import GoalChecker, NoValidControl
from nav2_pyif.geometry import limit_speed

from nav2_pyif_planners.follower import PathFollower
from nav2_pyif_planners.learned.features import features
from nav2_pyif_planners.learned.policy import Policy, default_weights, forward, import_jax


class LearnedController(PathFollower):
    """Needs input "scan" (sensor_msgs/LaserScan): in Nav2, the plugin's ``inputs``
    parameter; offline, ``nav2-pyif sim --scan``. Parameter ``weights``: the .npz written by
    ``nav2-pyif learn`` (default: the user's data directory)."""

    def configure(self) -> None:
        jax = import_jax()
        p = self.params
        path = Path(str(p.declare("weights", str(default_weights()), "policy .npz")))
        if not path.is_file():
            raise FileNotFoundError(f"no policy weights at {path}: run nav2-pyif learn first")
        self.policy = Policy.load(path)
        self.xy_goal_tolerance = p.declare("xy_goal_tolerance", 0.25, "[m] when no goal checker")
        self.index = 0
        device = jax.devices()[0]  # a GPU when JAX has one, else the CPU
        params = [
            (jax.device_put(w, device), jax.device_put(b, device)) for w, b in self.policy.layers
        ]
        self._infer = jax.jit(lambda x: forward(params, x))
        self.device = str(device)
        self._infer(np.zeros((1, len(self.policy.mean)), np.float32))  # compile now
        self.logger.info("policy %s on %s", path, self.device)

    def act(self, batch: np.ndarray) -> np.ndarray:
        """(B, F) features -> (B, 2) v [m/s], w [rad/s]: one call for a whole batch."""
        x = (batch - self.policy.mean) / self.policy.std
        out: np.ndarray = np.asarray(self._infer(x.astype(np.float32))) * self.policy.scale
        return out

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalChecker | None
    ) -> Any:
        x, y, yaw, path = self.track(pose)
        cmd = self.command(pose)
        if self.turn_at_goal(cmd, x, y, yaw, path, goal_checker):
            return cmd
        scan = self.inputs.get("scan")
        if scan is None:
            raise NoValidControl("no laser scan yet: the policy needs input 'scan'")
        f = features(
            scan.ranges,
            scan.angles,
            path[:, :2],
            self.index,
            (x, y, yaw),
            (velocity.linear.x, velocity.angular.z),
        )
        v, w = self.act(f[None])[0]
        top = limit_speed(float(self.policy.scale[0]), self.speed_limit)
        cmd.twist.linear.x = float(min(max(v, 0.0), top))
        cmd.twist.angular.z = float(w)
        return cmd
