"""The controller: Nav2 MPPI's MPPIController (controller.cpp) over the JAX optimizer. It
forwards, as Nav2's does: parameters (params.py), the plan (path.py), the optimization
(optimizer.py); here only the cycle's inputs, the costmap's upload and Nav2's fallback."""

from __future__ import annotations

import dataclasses
import math
import time
from typing import Any, ClassVar

import jax
import jax.numpy as jnp
import numpy as np
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Batch, Controller, GoalTolerances, InvalidController, NoValidControl, Plan
from nav2_pyif.geometry import pose_xy_yaw

from nav2_pyif_planners.mppi_nav2.costs import Grid
from nav2_pyif_planners.mppi_nav2.fleet import compute_batch
from nav2_pyif_planners.mppi_nav2.lanes import next_lane
from nav2_pyif_planners.mppi_nav2.optimizer import Outputs, noise_bank, pack, packed_step_on
from nav2_pyif_planners.mppi_nav2.params import read_settings
from nav2_pyif_planners.mppi_nav2.path import PathHandler, padded


class Nav2MPPI(Controller):
    """Nav2's MPPI controller (nav2_mppi_controller, Jazzy) in JAX: its critics, parameters
    (by Nav2's names and defaults: a Nav2 ``FollowPath`` MPPI block works as the plugin's
    parameters), motion models, acceleration limits, Savitzky-Golay smoothing and warm start.

    Parameters of its own, beside Nav2's: ``noise_sets`` (noise bank size, see
    optimizer.py), ``seed``, ``path_points`` (the pruned plan's fixed length in the step),
    ``track_unknown_space`` (the local costmap's: Nav2 reads it from the costmap),
    ``fleet_size`` (accepted for the other batched planners' YAML; Nav2MPPI's fleet runs
    each robot's own step, nothing compiled per size: ``compute_velocity_commands_batch``,
    fleet.py). Debug
    output: ``local_plan`` (the optimal trajectory)."""

    debug_outputs: ClassVar[dict[str, str]] = {"local_plan": "nav_msgs/msg/Path"}

    def configure(self) -> None:
        p = self.params
        frequency = self._context.nav2_params.get("controller_frequency")
        try:
            self.settings = read_settings(
                p,
                float(frequency) if isinstance(frequency, int | float) else None,
                self.logger,
                footprint=len(self.costmap.footprint) >= 3,  # as _check_footprint tells them
            )
        except ValueError as exc:
            raise InvalidController(str(exc)) from exc
        s = self.settings
        search = p.declare(
            "max_robot_pose_search_dist",
            0.5 * max(self.costmap.size_x, self.costmap.size_y) * self.costmap.resolution,
            "[m] along the plan to look for the robot's closest pose",
        )
        prune = p.declare("prune_distance", 1.5, "[m] plan ahead kept")
        self.path = PathHandler(prune, search)
        if s.path_points <= 0:  # room for a plan 1.5x as dense as the costmap, in 8s
            points = math.ceil(1.5 * prune / self.costmap.resolution / 8) * 8
            self.settings = s = dataclasses.replace(s, path_points=max(points, 16))
        self._subsampled = False
        self.regenerate_noises = p.declare("regenerate_noises", False, "new noise every cycle")
        self.retry_attempt_limit = p.declare("retry_attempt_limit", 1, "resets before failing")
        self.fleet_size = p.declare("fleet_size", 1, "robots a batched host serves at most")
        sets = p.declare("noise_sets", 8, "noise sets drawn at configure: a reset takes the next")
        self.rng = np.random.default_rng(p.declare("seed", 0, "noise seed"))
        # vx, (vy: only for Omni, the others have no lateral noise,) wz
        sigma = np.array([s.vx_std, s.vy_std, s.wz_std] if s.holonomic else [s.vx_std, s.wz_std])
        shape = (max(sets, 1), len(sigma), s.batch_size, s.time_steps)
        draw = self.rng.standard_normal(shape, np.float32)
        if not hasattr(self, "device"):  # a robot keeps its lane across reconfigures
            self.device = next_lane()
        self.bank = noise_bank(draw * sigma[None, :, None, None].astype(np.float32), self.device)
        # the lane's platform is fixed: its compiled step is looked up once, not every cycle
        self._step = packed_step_on(self.device.platform)
        self._check_footprint()
        self._noise_set = -1  # reset moves it to the bank's first set
        self._grid: Grid | None = None
        self._grid_version: int | None = None
        self.last_compute_s = 0.0
        self.reset()
        self._compile()
        self.logger.info(
            "Nav2 MPPI in JAX on %s: %d x %d, %s, critics %s", self.device,
            s.batch_size, s.time_steps, s.motion_model,
            ", ".join(c.name for c in s.critics if c.enabled),
        )  # fmt: skip

    def on_parameters_changed(self, changed: dict[str, Any]) -> None:
        self.configure()  # Nav2 resets the optimizer on a parameter change, too

    def _check_footprint(self) -> None:
        """Nav2's critics' checks of consider_footprint against the costmap's robot shape."""
        round_robot = len(self.costmap.footprint) < 3
        for critic in self.settings.critics:
            if not critic.enabled or critic.name not in ("CostCritic", "ObstaclesCritic"):
                continue
            if round_robot == critic["consider_footprint"]:
                self.logger.warning(
                    "Inconsistent configuration in collision checking. Please verify the "
                    "robot's shape settings in both the costmap and the %s.", critic.name,
                )  # fmt: skip
                if round_robot:
                    raise InvalidController(
                        "Considering footprint in collision checking but no robot footprint "
                        "provided in the costmap."
                    )

    def _upload_costmap(self) -> Grid:
        """The costmap on the device, once per costmap version."""
        costmap = self.costmap
        if self._grid is not None and self._grid_version == costmap.version:
            return self._grid
        inflation = costmap.inflation
        possible, radius, scale = -1.0, 0.0, 0.0
        if inflation is not None:
            radius, scale = inflation.inflation_radius, inflation.cost_scaling_factor
            possible = (
                0.0 if radius < costmap.circumscribed_radius else costmap.circumscribed_cost()
            )
        grid = Grid(
            data=np.asarray(costmap.data),
            meta=np.asarray([costmap.origin_x, costmap.origin_y, costmap.resolution], np.float32),
            outline=np.asarray(costmap.footprint_outline(costmap.resolution), np.float32),
            robot=np.asarray([possible, costmap.inscribed_radius, radius, scale], np.float32),
        )
        self._grid = jax.device_put(grid, self.device)
        self._grid_version = costmap.version
        return self._grid

    def _compile(self) -> None:
        """Compile the step now (configure may take seconds; a cycle may not)."""
        s = self.settings
        straight = np.column_stack([np.linspace(0, 1, 5), np.zeros(5), np.zeros(5)])
        path, count = padded(straight, s.path_points)
        inputs = self._inputs(np.zeros(3), np.zeros(3), straight[-1], path, count, None)
        for _ in range(2):  # the second run: XLA's first-execution set-up, off the first cycle
            jax.block_until_ready(self._run(inputs))  # the warm start and history untouched

    def reset(self) -> None:
        """Nav2's Optimizer::reset: the warm start and the smoothing's history forgotten, and
        new noise (Nav2 draws a set on every reset: each goal, each fallback): the bank's next
        set."""
        s = self.settings
        self._noise_set = (self._noise_set + 1) % self.bank.shape[0]
        self.sequence = jnp.zeros((3, s.time_steps), jnp.float32, device=self.device)
        self.history = jnp.zeros((4, 3), jnp.float32, device=self.device)
        self._optimal = self.sequence

    def set_plan(self, plan: Plan) -> None:
        super().set_plan(plan)
        self.path.set_plan(plan.xy_yaw)

    def _limits(self) -> np.ndarray:
        """(vx_max, vx_min, vy_max, wz_max) after Nav2's speed limit (all scaled alike)."""
        s = self.settings
        ratio = 1.0
        if self.speed_limit is not None:
            value, percentage = self.speed_limit
            ratio = value / 100.0 if percentage else value / s.vx_max
        return np.array([s.vx_max, s.vx_min, s.vy_max, s.wz_max], np.float32) * ratio

    def _inputs(
        self,
        pose: np.ndarray,
        speed: np.ndarray,
        goal: np.ndarray,
        path: np.ndarray,
        count: int,
        goal_checker: GoalTolerances | None,
    ) -> np.ndarray:
        tolerance = goal_checker.xy_goal_tolerance if goal_checker else -1.0
        return pack(pose, speed, goal, self._limits(), tolerance, path, count)

    def pick_noise(self, inputs: np.ndarray) -> None:
        """This cycle's noise set and roll into packed inputs: the set of the last reset,
        unrolled, unless regenerate_noises (a random set and roll each cycle; optimizer.py)."""
        if self.regenerate_noises:
            inputs[5, :2] = (
                self.rng.integers(self.bank.shape[0]),
                self.rng.integers(self.settings.batch_size),
            )
        else:
            inputs[5, :2] = (self._noise_set, 0)

    def _run(self, inputs: np.ndarray) -> Outputs:
        """The compiled step on packed inputs (optimizer.pack), this cycle's noise picked."""
        self.pick_noise(inputs)
        out: Outputs = self._step(
            self.sequence, self.history, self.bank, inputs, self._upload_costmap(), self.settings
        )
        return out

    def compute_velocity_commands(
        self, pose: Any, velocity: Any, goal_checker: GoalTolerances | None
    ) -> Any:
        started = time.perf_counter()
        state = np.array(pose_xy_yaw(pose))
        inputs = self.cycle_inputs(state, velocity, goal_checker)
        command = self.optimise(inputs)
        if self.debug_wanted("local_plan"):
            self._publish_local_plan(state, np.asarray(self._optimal))
        cmd = self.twist(pose, command)
        self.last_compute_s = time.perf_counter() - started
        return cmd

    def cycle_inputs(
        self, state: np.ndarray, velocity: Any, goal_checker: GoalTolerances | None
    ) -> np.ndarray:
        """The step's packed inputs for the robot at ``state`` (x, y, yaw): the plan pruned (Nav2's
        path handler) and padded, the speed, the goal, the limits."""
        if self.plan is None:
            raise NoValidControl("no plan to follow")
        pruned = self.path.transform(float(state[0]), float(state[1]), self.costmap)
        if len(pruned) > self.settings.path_points and not self._subsampled:
            self._subsampled = True
            self.logger.warning(
                "the pruned plan has %d poses, more than path_points (%d): subsampled (plan "
                "offsets then count fewer, larger steps; raise path_points)",
                len(pruned), self.settings.path_points,
            )  # fmt: skip
        path, count = padded(pruned, self.settings.path_points)
        speed = np.array([velocity.linear.x, velocity.linear.y, velocity.angular.z])
        return self._inputs(state, speed, self.plan.xy_yaw[-1], path, count, goal_checker)

    def optimise(self, inputs: np.ndarray, dispatched: Outputs | None = None) -> np.ndarray:
        """Nav2's evalControl: the step (``dispatched``: one already started on ``inputs``, a
        fleet's), reset and retried while every rollout collides; the warm start kept.
        -> (vx, vy, wz)."""
        failures = 0
        while True:
            out = self._run(inputs) if dispatched is None else dispatched
            dispatched = None
            reply = np.asarray(out.reply, np.float64)
            command, fail = reply[:3], reply[3] != 0.0
            if not fail:
                break
            self.reset()
            failures += 1
            if failures > self.retry_attempt_limit:
                raise NoValidControl("Optimizer fail to compute path")
        self.sequence, self.history, self._optimal = out.sequence, out.history, out.optimal
        return self.checked(command)

    @staticmethod
    def checked(command: np.ndarray) -> np.ndarray:
        if not np.isfinite(command).all():
            raise NoValidControl("MPPI produced a non-finite command")
        return command

    @classmethod
    def compute_velocity_commands_batch(cls, batch: Batch) -> list[Any]:
        """The cycles of a fleet, each robot's step dispatched before any is read (fleet.py)."""
        return compute_batch(batch)

    def twist(self, pose: Any, command: np.ndarray) -> Any:
        """The command as the TwistStamped Nav2 expects: the pose's stamp, the base frame."""
        cmd = TwistStamped(header=pose.header)
        cmd.header.frame_id = self.robot_base_frame
        cmd.twist.linear.x, cmd.twist.linear.y, cmd.twist.angular.z = (float(v) for v in command)
        return cmd

    def _publish_local_plan(self, state: np.ndarray, optimal: np.ndarray) -> None:
        """The optimal sequence (3, T) rolled out from ``state`` as (T, 3) x, y, yaw."""
        dt = self.settings.model_dt
        yaw = state[2] + np.cumsum(optimal[2] * dt)
        before = np.concatenate([[state[2]], yaw[:-1]])
        dx = optimal[0] * np.cos(before) - optimal[1] * np.sin(before)
        dy = optimal[0] * np.sin(before) + optimal[1] * np.cos(before)
        x, y = state[0] + np.cumsum(dx * dt), state[1] + np.cumsum(dy * dt)
        self.publish_debug("local_plan", np.column_stack([x, y, yaw]))
