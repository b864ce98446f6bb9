"""Demonstrations: the reference MPPI drives, and each cycle's (features, command) is kept.

Served by the planner host like any controller, with the runner's simulated scan as input
"scan". The robot executes the command plus a little noise (``action_noise``), and the clean
command is the label: the policy then also sees how to recover from small deviations of its
own (DART-style), which plain demonstrations never show it."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from nav2_pyif import GoalTolerances
from nav2_pyif.geometry import pose_xy_yaw

from nav2_pyif_planners.learned.features import features
from nav2_pyif_planners.mppi import MPPI


class RecordingMPPI(MPPI):
    def configure(self) -> None:
        super().configure()
        self.record_to = str(self.params.declare("record_to", "", "the .npz file to write"))
        self.action_noise = self.params.declare("action_noise", 0.1, "executed noise std")
        self.noise_rng = np.random.default_rng(int(self.seed) + 1)
        self.samples: list[np.ndarray] = []
        self.labels: list[tuple[float, float]] = []

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        cmd = super().compute_velocity_commands(pose, velocity, goal_checker)
        scan = self.inputs.get("scan")
        if scan is None or self.plan is None:
            return cmd
        v, w = cmd.twist.linear.x, cmd.twist.angular.z
        self.samples.append(
            features(
                scan.ranges,
                scan.angles,
                self.plan.xy_yaw[:, :2],
                self.index,
                pose_xy_yaw(pose),
                (velocity.linear.x, velocity.angular.z),
            )
        )
        self.labels.append((v, w))
        noise = self.noise_rng.normal(0.0, self.action_noise, 2) * (0.5, 2.0)
        cmd.twist.linear.x = float(np.clip(v + noise[0], 0.0, self.vx_max))
        cmd.twist.angular.z = float(np.clip(w + noise[1], -self.wz_max, self.wz_max))
        return cmd

    def deactivate(self) -> None:
        """The run is over: write what was seen (the runner deactivates before cleanup)."""
        if self.record_to and self.samples:
            Path(self.record_to).parent.mkdir(parents=True, exist_ok=True)
            np.savez(
                self.record_to,
                x=np.stack(self.samples),
                y=np.asarray(self.labels, dtype=np.float32),
            )
