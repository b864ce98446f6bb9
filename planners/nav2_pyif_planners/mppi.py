"""Model predictive path integral control (after Nav2's MPPI controller), vectorised in NumPy.

Each cycle samples ``batch_size`` noisy control sequences (vx, wz) around the previous
optimum, rolls a unicycle model forward ``time_steps`` x ``model_dt`` seconds, scores every
rollout and moves the optimum towards the softmin-weighted average of the noise:

    cost = w_path * mean distance to the local plan           (follow the path)
         + w_progress * distance from the end to a point down the plan   (make progress)
         + w_obstacle * mean footprint cost / 252  +  w_collision * [footprint cost >= 253]
         + temperature * gamma * sum(u . Sigma^-1 . eps)       (control effort, MPPI's term)

Footprint costs use ``Costmap.footprint_costs`` over all (rollouts, steps) poses at once.
Within the goal tolerance the robot turns in place to the goal's heading.
"""

from __future__ import annotations

import math
import time
from typing import Any, ClassVar

import numpy as np
from nav2_pyif import Costmap, GoalTolerances, NoValidControl
from nav2_pyif.geometry import limit_speed

from nav2_pyif_planners.follower import PathFollower

LOCAL_POINTS = 24  # local plan points the path cost compares rollouts with, at most
DRAWN = 40  # sampled rollouts returned as the "trajectories" debug output, at most


class MPPI(PathFollower):
    """Debug outputs, as Nav2's MPPI publishes them: ``trajectories`` (a sample of the
    rollouts) and ``local_plan`` (the optimal trajectory)."""

    debug_outputs: ClassVar[dict[str, str]] = {
        "trajectories": "visualization_msgs/msg/MarkerArray",
        "local_plan": "nav_msgs/msg/Path",
    }

    def configure(self) -> None:
        p = self.params
        self.batch_size = p.declare("batch_size", 1000, "rollouts per cycle")
        self.time_steps = p.declare("time_steps", 40, "steps per rollout")
        self.model_dt = p.declare("model_dt", 0.05, "[s] per step")
        self.temperature = p.declare("temperature", 0.3)
        self.gamma = p.declare("gamma", 0.015)
        self.vx_max = p.declare("vx_max", 0.5, "[m/s]")
        self.vx_min = p.declare("vx_min", 0.0, "[m/s]")
        self.wz_max = p.declare("wz_max", 1.9, "[rad/s]")
        self.vx_std = p.declare("vx_std", 0.2)
        self.wz_std = p.declare("wz_std", 0.4)
        self.w_path = p.declare("path_weight", 5.0)
        self.w_progress = p.declare("progress_weight", 3.0)
        self.w_obstacle = p.declare("obstacle_weight", 2.0)
        self.w_collision = p.declare("collision_cost", 10000.0)
        self.xy_goal_tolerance = p.declare("xy_goal_tolerance", 0.25, "[m] when no goal checker")
        self.seed = p.declare("seed", 0)
        self.rng = np.random.default_rng(self.seed)
        self.optimal = np.zeros((self.time_steps, 2))
        self.index = 0
        self.outline: np.ndarray | None = None
        self.last_compute_s = 0.0
        self._along: tuple[object, np.ndarray] | None = None  # (plan, its arc lengths)

    def reset(self) -> None:
        self._clear_optimum()
        self.index = 0

    def _clear_optimum(self) -> None:
        """Forget the warm start (at the goal, on reset): the next cycle starts from rest."""
        self.optimal[:] = 0.0

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        started = time.perf_counter()
        x, y, yaw, path = self.track(pose)
        cmd = self.command(pose)
        if self.turn_at_goal(cmd, x, y, yaw, path, goal_checker):
            self._clear_optimum()
            return cmd
        vx, wz = self._optimise(np.array([x, y, yaw]), path[:, :2])
        if not (math.isfinite(vx) and math.isfinite(wz)):
            raise NoValidControl("MPPI produced a non-finite command")
        cmd.twist.linear.x, cmd.twist.angular.z = vx, wz
        self.last_compute_s = time.perf_counter() - started
        return cmd

    def _optimise(self, state: np.ndarray, path_xy: np.ndarray) -> tuple[float, float]:
        k, t, dt = self.batch_size, self.time_steps, self.model_dt
        vx_top = limit_speed(self.vx_max, self.speed_limit)
        sigma = np.array([self.vx_std, self.wz_std])
        noise = self.rng.standard_normal((k, t, 2)) * sigma
        controls = self.optimal[None] + noise
        np.clip(controls[..., 0], self.vx_min, vx_top, out=controls[..., 0])
        np.clip(controls[..., 1], -self.wz_max, self.wz_max, out=controls[..., 1])
        noise = controls - self.optimal[None]

        rollouts = self._rollout(state, controls, dt)  # (k, t, 3)
        if self.debug_wanted("trajectories"):  # every (k / DRAWN)-th: enough to see
            self.publish_debug("trajectories", rollouts[:: max(1, k // DRAWN), :, :2])
        costs = self._score(rollouts, path_xy, vx_top)
        costs += (
            self.temperature * self.gamma * np.einsum("tc,ktc->k", self.optimal / sigma**2, noise)
        )

        weights = np.exp(-(costs - costs.min()) / self.temperature)
        weights /= weights.sum()
        self.optimal = self.optimal + np.einsum("k,ktc->tc", weights, noise)
        command = self.optimal[0].copy()
        self._publish_optimal(state, self.optimal)
        self.optimal = np.roll(self.optimal, -1, axis=0)  # warm start for the next cycle
        self.optimal[-1] = self.optimal[-2]
        return float(command[0]), float(command[1])

    def _publish_optimal(self, state: np.ndarray, optimal: np.ndarray) -> None:
        """The ``local_plan`` debug output: the optimum (T, 2) rolled out from ``state``."""
        if self.debug_wanted("local_plan"):
            self.publish_debug("local_plan", self._rollout(state, optimal[None], self.model_dt)[0])

    @staticmethod
    def _rollout(state: np.ndarray, controls: np.ndarray, dt: float) -> np.ndarray:
        yaw = state[2] + np.cumsum(controls[..., 1] * dt, axis=1)
        heading = np.concatenate([np.full((controls.shape[0], 1), state[2]), yaw[:, :-1]], axis=1)
        x = state[0] + np.cumsum(controls[..., 0] * np.cos(heading) * dt, axis=1)
        y = state[1] + np.cumsum(controls[..., 0] * np.sin(heading) * dt, axis=1)
        return np.stack([x, y, yaw], axis=-1)

    def _score(self, rollouts: np.ndarray, path_xy: np.ndarray, vx_top: float) -> np.ndarray:
        local = self._local_path(path_xy, vx_top)
        sub = rollouts[:, 3::4, :2].reshape(-1, 2)  # every 4th step: enough for the path
        # squared distances to every local plan point as one matrix product (BLAS), not a
        # (rollouts, steps, points, 2) difference array
        d2 = (sub**2).sum(axis=1)[:, None] + (local**2).sum(axis=1)[None] - 2.0 * sub @ local.T
        nearest = np.sqrt(np.maximum(d2.min(axis=1), 0.0)).reshape(rollouts.shape[0], -1)
        path_cost = nearest.mean(axis=1)
        end = rollouts[:, -1, :2] - local[-1]
        progress = np.sqrt((end**2).sum(axis=1))

        costmap = self.costmap
        if self.outline is None or len(self.outline) == 0:
            self.outline = costmap.footprint_outline(spacing=max(costmap.resolution, 0.2))
        # Unknown and off-map cells count as free, point by point (a lethal cell under the
        # rest of the footprint still counts near the rolling window's edge).
        footprint = costmap.footprint_costs(rollouts[:, ::2], self.outline, unknown_as=0)
        footprint = footprint.astype(np.float64)
        collision = (footprint >= Costmap.INSCRIBED).any(axis=1)
        obstacle = (footprint / 252.0).mean(axis=1)
        total: np.ndarray = (
            self.w_path * path_cost
            + self.w_progress * progress
            + self.w_obstacle * obstacle
            + self.w_collision * collision
        )
        return total

    def _local_path(self, path_xy: np.ndarray, vx_top: float) -> np.ndarray:
        """Plan points from the closest one to as far as the horizon reaches at ``vx_top``
        (plus 0.5 m), at most LOCAL_POINTS of them."""
        reach = vx_top * self.time_steps * self.model_dt + 0.5
        along = self._arc_length(path_xy)
        start = min(self.index, len(path_xy) - 1)
        end = int(np.searchsorted(along, along[start] + reach)) + 1
        local = path_xy[start : max(end, start + 1)]
        if len(local) > LOCAL_POINTS:
            spread = np.arange(LOCAL_POINTS) * ((len(local) - 1) / (LOCAL_POINTS - 1))
            local = local[np.rint(spread).astype(int)]
        return local

    def _arc_length(self, path_xy: np.ndarray) -> np.ndarray:
        """(N,) arc length [m] from the plan's start to each point: once per plan, not per
        cycle (summed per cycle, with the rest of this method, they were most of a batched
        robot's Python time in the fleet benchmark, on a 100-point plan)."""
        plan, cached = self.plan, self._along
        if cached is None or cached[0] is not plan or len(cached[1]) != len(path_xy):
            seg = np.hypot(*np.diff(path_xy, axis=0).T) if len(path_xy) > 1 else np.zeros(0)
            cached = self._along = (plan, np.concatenate([[0.0], np.cumsum(seg)]))
        along: np.ndarray = cached[1]
        return along
