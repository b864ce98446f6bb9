"""MPPI in JAX: the NumPy ``MPPI``'s optimisation as one jit-compiled function, on a GPU when
JAX has one (the CUDA image: docker/compose.yaml's gpu profile), else on the CPU.

Batched (``planner-host --batch``): the rollouts of every robot in a batch in one
jit-compiled call (``mppi_fleet``, ``mppi_step`` vmapped over a robot axis). Robots of equal
shapes (rollouts, steps, costmap size, footprint) share a call; their number is padded to
``nav2_pyif.batch.bucket`` sizes, compiled in ``configure`` up to the ``fleet_size``
parameter, so a robot joining never compiles mid-cycle. Each robot's state (PRNG key, warm
start) lives in NumPy between cycles: one transfer to the device and one back per batch, none
inside the step.

Same parameters, cost terms and warm start as ``nav2_pyif_planners.mppi.MPPI``; what differs:
sampling uses JAX's counter-based PRNG, arithmetic is float32, and the footprint's cost at a
pose is one read of per-heading maximum maps (``footprint_maps``: at most about a cell's
margin above ``MPPI``'s outline reads and never below them, for a polygon at each of its map
headings, 22.5 degrees apart), built and copied to the device once per costmap version. The
function is compiled in ``configure`` for the costmap's shape, so the first control cycle does
not pay for compilation (a costmap of a new shape recompiles once). Needs JAX:
``python -m pip install 'jax>=0.4.30'`` (CPU) or ``jax[cuda12]``; the bootstrap's default
extras (dev) include it.
"""

from __future__ import annotations

import math
import time
from functools import partial
from typing import Any, ClassVar

import numpy as np

try:
    import jax
    import jax.numpy as jnp
except ImportError as exc:  # a clear reason at load time, not a NameError mid-run
    import sys

    raise ImportError(
        f"nav2_pyif_planners.mppi_jax needs JAX, which {sys.executable} lacks: "
        f"{sys.executable} -m pip install 'jax>=0.4.30' (CPU; 'jax[cuda12]' for NVIDIA GPUs); "
        "in a checkout, NAV2_PYIF_EXTRAS=dev,jax ./scripts/bootstrap.sh"
    ) from exc

from nav2_pyif import Batch, Costmap, NoValidControl
from nav2_pyif.batch import bucket, buckets, pad_rows
from nav2_pyif.geometry import limit_speed

from nav2_pyif_planners.footprint_maps import TURN, footprint_maps
from nav2_pyif_planners.mppi import LOCAL_POINTS, MPPI

#: JAX computes on the CPU: a batch's footprint maps are stacked in NumPy (a copy, where
#: ``jnp.stack`` is an XLA call: 15 % of a batch of 12 robots); on an accelerator they stay
#: on it, stacked there.
_HOST_IS_DEVICE = jax.default_backend() == "cpu"


def _mppi_update(
    normal: Any,
    optimal: Any,
    state: Any,
    local: Any,
    layers: Any,
    origin: Any,
    settings: Any,
) -> tuple[Any, Any]:
    """One MPPI iteration from standard normal draws (2, rollouts, steps) -> (shifted
    optimum for the warm start, command (vx, wz)); the footprint's costs from ``layers``, the
    robot's ``FootprintMaps``.

    Written for XLA on a CPU as much as a GPU: vx and wz as separate (rollouts, steps)
    arrays (a trailing axis of 2 defeats vectorisation), cumulative sums as products with a
    triangular matrix (XLA's cumsum is a quadratic reduce-window on a CPU), distances to the
    plan from split coordinates: 5-25x faster on a CPU than the obvious form. The footprint's
    cost is one read per pose (``footprint_maps``), not one per outline point: those reads
    were 60 % of the kernel (31 of 50 ms for 32 robots on one thread)."""
    (dt, vx_min, vx_top, wz_max, vx_std, wz_std, temperature, gamma) = settings[:8]
    (w_path, w_progress, w_obstacle, w_collision, resolution) = settings[8:]
    steps = optimal.shape[0]
    # x @ upper: the running sum along the steps
    upper = jnp.triu(jnp.ones((steps, steps), jnp.float32))
    summed = partial(jnp.matmul, precision=jax.lax.Precision.HIGHEST)  # no TF32 on a GPU
    vx = jnp.clip(optimal[:, 0] + normal[0] * vx_std, vx_min, vx_top)
    wz = jnp.clip(optimal[:, 1] + normal[1] * wz_std, -wz_max, wz_max)
    noise_vx, noise_wz = vx - optimal[:, 0], wz - optimal[:, 1]

    # unicycle rollouts (batch, steps), as MPPI._rollout: each step moves along the heading
    # before its turn; x and y summed in one product (one pass over the triangle, not two)
    yaw = state[2] + summed(wz * dt, upper)
    heading = yaw - wz * dt
    rollouts = vx.shape[0]
    moved = jnp.concatenate([vx * jnp.cos(heading) * dt, vx * jnp.sin(heading) * dt])
    xy = summed(moved, upper)
    x, y = state[0] + xy[:rollouts], state[1] + xy[rollouts:]

    # follow the path and progress along it, as MPPI._score
    dx = x[:, 3::4, None] - local[:, 0]
    dy = y[:, 3::4, None] - local[:, 1]
    path_cost = jnp.sqrt((dx * dx + dy * dy).min(axis=-1)).mean(axis=1)
    progress = jnp.hypot(x[:, -1] - local[-1, 0], y[:, -1] - local[-1, 1])

    # footprint costs at every other step: one read per pose of the per-heading maximum maps
    # (footprint_maps: unknown and off-map cells count as free, as MPPI's
    # footprint_costs(..., unknown_as=0)); a pose off the padded map reads its free edge
    headings, rows, cols = layers.shape
    px, py, pyaw = x[:, ::2], y[:, ::2], yaw[:, ::2]
    col = jnp.clip(jnp.floor((px - origin[0]) / resolution).astype(jnp.int32), 0, cols - 1)
    row = jnp.clip(jnp.floor((py - origin[1]) / resolution).astype(jnp.int32), 0, rows - 1)
    turn = jnp.round(pyaw * (TURN / (2 * math.pi))).astype(jnp.int32) & (headings - 1)
    worst = layers.reshape(-1)[(turn * rows + row) * cols + col].astype(jnp.float32)
    collision = (worst >= Costmap.INSCRIBED).any(axis=1)
    obstacle = (worst / 252.0).mean(axis=1)

    total = (
        w_path * path_cost
        + w_progress * progress
        + w_obstacle * obstacle
        + w_collision * collision
        + temperature
        * gamma
        * (noise_vx @ (optimal[:, 0] / vx_std**2) + noise_wz @ (optimal[:, 1] / wz_std**2))
    )
    weights = jax.nn.softmax(-(total - total.min()) / temperature)
    optimal = optimal + jnp.stack([weights @ noise_vx, weights @ noise_wz], axis=-1)
    command = optimal[0]
    shifted = jnp.concatenate([optimal[1:], optimal[-1:]], axis=0)
    return shifted, command


@partial(jax.jit, static_argnames=("batch_size",))
def mppi_step(
    key: Any,
    optimal: Any,
    state: Any,
    local: Any,
    layers: Any,
    origin: Any,
    settings: Any,
    batch_size: int,
) -> tuple[Any, Any, Any]:
    """One MPPI iteration -> (next key, shifted optimum for warm start, command (vx, wz))."""
    key, draw = jax.random.split(key)
    normal = jax.random.normal(draw, (2, batch_size, optimal.shape[0]))
    return (key, *_mppi_update(normal, optimal, state, local, layers, origin, settings))


@partial(jax.jit, static_argnames=("batch_size", "steps"))
def _draw(key: Any, batch_size: int, steps: int) -> tuple[Any, Any]:
    key, draw = jax.random.split(key)
    return key, jax.random.normal(draw, (2, batch_size, steps))


_update_fleet = jax.jit(jax.vmap(_mppi_update, in_axes=(None, 0, 0, 0, 0, 0, 0)))


def mppi_fleet(
    key: Any,
    optimal: Any,
    state: Any,
    local: Any,
    layers: Any,
    origin: Any,
    settings: Any,
    batch_size: int,
) -> tuple[Any, Any, Any]:
    """The MPPI iteration of R robots in one call: ``key`` (2,) uint32, the others with a
    leading robot axis: optimal (R, T, 2), state (R, 3), local (R, LOCAL_POINTS, 2), layers
    (R, headings, H, W) uint8 (``FootprintMaps.layers``), origin (R, 2) (their origin),
    settings (R, 13) -> (next key, shifted optima (R, T, 2), commands (R, 2) vx [m/s],
    wz [rad/s]).

    The robots share one draw of standard normal noise (common random numbers: each robot's
    samples are still i.i.d. Gaussian, scaled by its own sigma), so sampling costs the same
    for 1 robot or 100. Two compiled calls, the draw and the update, the noise staying on the
    device between them: compiled together, XLA computes the draw many times over (measured
    on a CPU: 18 ms of a 47 ms batch of 32 robots)."""
    key, normal = _draw(key, batch_size=batch_size, steps=optimal.shape[1])
    return (key, *_update_fleet(normal, optimal, state, local, layers, origin, settings))


class MPPIJax(MPPI):
    """``MPPI`` with the optimisation in JAX. Parameters: those of ``MPPI``, and
    ``fleet_size``: the most robots a batched host serves with this planner (their batch
    shapes are compiled in ``configure``). Debug output: ``local_plan`` (the rollouts stay on
    the device)."""

    debug_outputs: ClassVar[dict[str, str]] = {"local_plan": "nav_msgs/msg/Path"}

    def configure(self) -> None:
        super().configure()
        self.fleet_size = self.params.declare(
            "fleet_size", 1, "robots a batched host serves at most: compiled in configure"
        )
        self._grid_version: int | None = None
        self._upload_costmap()
        # Compile now (configure may take seconds; a control cycle may not): each padded
        # batch size up to fleet_size, once per process (JAX caches compiled shapes).
        state = np.zeros(3)
        path = np.column_stack([np.linspace(0.0, 1.0, 5), np.zeros(5)])
        for size in buckets(int(self.fleet_size)):
            self._restart_sampling()
            _optimise_fleet([(self, state, path)], pad_to=size)
        self._restart_sampling()  # the warm-up leaves no trace
        self.logger.info("MPPI in JAX on %s", jax.devices()[0])

    def _restart_sampling(self) -> None:
        self._key = np.asarray(jax.random.PRNGKey(self.seed))
        self._clear_optimum()

    def _clear_optimum(self) -> None:
        self._optimal = np.zeros((self.time_steps, 2), np.float32)

    def _upload_costmap(self) -> None:
        costmap = self.costmap
        if self._grid_version == costmap.version and self.outline is not None:
            return
        self.outline = costmap.footprint_outline(spacing=max(costmap.resolution, 0.2))
        maps = footprint_maps(costmap, self.outline)
        self._layers = maps.layers if _HOST_IS_DEVICE else jnp.asarray(maps.layers)
        self._origin = maps.origin.astype(np.float32)
        self._grid_version = costmap.version

    def _optimise(self, state: np.ndarray, path_xy: np.ndarray) -> tuple[float, float]:
        return _optimise_fleet([(self, state, path_xy)])[0]

    def _step_inputs(self, state: np.ndarray, path_xy: np.ndarray) -> tuple[np.ndarray, ...]:
        """This robot's (state, padded local plan, settings) for ``mppi_fleet``."""
        self._upload_costmap()
        vx_top = limit_speed(self.vx_max, self.speed_limit)
        local = self._local_path(path_xy, vx_top)
        # padded to LOCAL_POINTS with its last point: one compiled shape whatever its length
        padded = np.concatenate([local, np.repeat(local[-1:], LOCAL_POINTS - len(local), 0)])
        settings = np.asarray(
            [
                self.model_dt, self.vx_min, vx_top, self.wz_max, self.vx_std, self.wz_std,
                self.temperature, self.gamma, self.w_path, self.w_progress, self.w_obstacle,
                self.w_collision, self.costmap.resolution,
            ],
            np.float32,
        )  # fmt: skip
        return state.astype(np.float32), padded.astype(np.float32), settings

    def _shape(self) -> tuple[Any, ...]:
        """What must match for robots to share a compiled call."""
        self._upload_costmap()
        return (self.batch_size, self.time_steps, self._layers.shape)

    @classmethod
    def compute_velocity_commands_batch(cls, batch: Batch) -> list[Any]:
        """Every robot's cycle: at the goal, its turn in place; else its MPPI iteration, all
        of them in one ``mppi_fleet`` call per shape. A robot's own error is its item."""
        out: list[Any] = [None] * len(batch)
        todo: dict[tuple[Any, ...], list[tuple[int, MPPIJax, np.ndarray, np.ndarray]]] = {}
        for i, robot in enumerate(batch.planners):
            assert isinstance(robot, MPPIJax)
            pose = batch.pose_messages[i]
            try:
                x, y, yaw, path = robot.track(pose)
                out[i] = cmd = robot.command(pose)
                if robot.turn_at_goal(cmd, x, y, yaw, path, batch.goal_checkers[i]):
                    robot._clear_optimum()
                    continue
                todo.setdefault(robot._shape(), []).append(
                    (i, robot, np.array([x, y, yaw]), path[:, :2])
                )
            except Exception as exc:  # this robot's own error (no plan, ...)
                out[i] = exc
        for group in todo.values():
            started = time.perf_counter()
            commands = _optimise_fleet([(robot, state, path) for _, robot, state, path in group])
            for (i, robot, _, _), (vx, wz) in zip(group, commands, strict=True):
                robot.last_compute_s = time.perf_counter() - started
                if not (math.isfinite(vx) and math.isfinite(wz)):
                    out[i] = NoValidControl("MPPI produced a non-finite command")
                else:
                    out[i].twist.linear.x, out[i].twist.angular.z = vx, wz
        return out


def _optimise_fleet(
    robots: list[tuple[MPPIJax, np.ndarray, np.ndarray]], pad_to: int = 0
) -> list[tuple[float, float]]:
    """One MPPI iteration of each (robot, state (3,), plan xy (N, 2)), robots of one shape,
    in one ``mppi_fleet`` call; their keys and warm starts updated. -> (vx, wz) per robot."""
    inputs = [robot._step_inputs(state, path) for robot, state, path in robots]
    size = max(pad_to, bucket(len(robots)))
    layers = [robot._layers for robot, _, _ in robots]
    layers += layers[-1:] * (size - len(layers))

    def stacked(values: list[np.ndarray]) -> np.ndarray:
        return pad_rows(np.stack(values), size)

    key, optimal, commands = mppi_fleet(
        robots[0][0]._key,  # the batch's draw: from its first robot's stream
        stacked([robot._optimal for robot, _, _ in robots]),
        stacked([state for state, _, _ in inputs]),
        stacked([local for _, local, _ in inputs]),
        (np.stack if _HOST_IS_DEVICE else jnp.stack)(layers),
        stacked([robot._origin for robot, _, _ in robots]),
        stacked([settings for _, _, settings in inputs]),
        batch_size=robots[0][0].batch_size,
    )
    key, optimal, commands = (np.asarray(a) for a in (key, optimal, commands))
    results = []
    for n, (robot, state, _) in enumerate(robots):
        robot._key, robot._optimal = key, optimal[n]
        vx, wz = (float(v) for v in commands[n])
        if robot.debug_wanted("local_plan"):  # the optimum before its shift for the warm start
            shifted = optimal[n].astype(np.float64)
            robot._publish_optimal(state, np.vstack([[vx, wz], shifted[:-1]]))
        results.append((vx, wz))
    return results
