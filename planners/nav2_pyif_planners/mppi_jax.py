"""MPPI in JAX: the NumPy ``MPPI``'s optimisation as one jit-compiled function, on a GPU when
JAX has one (the CUDA image: docker/compose.yaml's gpu profile), else on the CPU.

Same parameters, cost terms and warm start as ``nav2_pyif_planners.mppi.MPPI``; what differs:
sampling uses JAX's counter-based PRNG, arithmetic is float32, and the costmap is copied to the
device once per costmap version. The function is compiled in ``configure`` for the costmap's
shape, so the first control cycle does not pay for compilation (a costmap of a new shape
recompiles once). Needs JAX: ``python -m pip install 'jax>=0.4.30'`` (CPU) or ``jax[cuda12]``;
the bootstrap's default extras (dev) include it.
"""

from __future__ import annotations

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

from nav2_pyif import Costmap
from nav2_pyif.geometry import limit_speed

from nav2_pyif_planners.mppi import LOCAL_POINTS, MPPI


@partial(jax.jit, static_argnames=("batch_size",))
def mppi_step(
    key: Any,
    optimal: Any,
    state: Any,
    local: Any,
    grid: Any,
    origin: Any,
    outline: Any,
    settings: Any,
    batch_size: int,
) -> tuple[Any, Any, Any]:
    """One MPPI iteration -> (next key, shifted optimum for warm start, command (vx, wz))."""
    (dt, vx_min, vx_top, wz_max, vx_std, wz_std, temperature, gamma) = settings[:8]
    (w_path, w_progress, w_obstacle, w_collision, resolution) = settings[8:]
    steps = optimal.shape[0]
    key, draw = jax.random.split(key)
    sigma = jnp.stack([vx_std, wz_std])
    controls = optimal[None] + jax.random.normal(draw, (batch_size, steps, 2)) * sigma
    controls = jnp.stack(
        [
            jnp.clip(controls[..., 0], vx_min, vx_top),
            jnp.clip(controls[..., 1], -wz_max, wz_max),
        ],
        axis=-1,
    )
    noise = controls - optimal[None]

    # unicycle rollouts (batch, steps, 3), as MPPI._rollout
    yaw = state[2] + jnp.cumsum(controls[..., 1] * dt, axis=1)
    heading = jnp.concatenate([jnp.full((batch_size, 1), state[2]), yaw[:, :-1]], axis=1)
    x = state[0] + jnp.cumsum(controls[..., 0] * jnp.cos(heading) * dt, axis=1)
    y = state[1] + jnp.cumsum(controls[..., 0] * jnp.sin(heading) * dt, axis=1)

    # follow the path and progress along it, as MPPI._score
    sub = jnp.stack([x[:, 3::4], y[:, 3::4]], axis=-1)
    d2 = ((sub[:, :, None, :] - local[None, None]) ** 2).sum(axis=-1)
    path_cost = jnp.sqrt(d2.min(axis=-1)).mean(axis=1)
    progress = jnp.hypot(x[:, -1] - local[-1, 0], y[:, -1] - local[-1, 1])

    # footprint costs at every other step: max over the outline; unknown and off-map cells
    # count as free point by point, as MPPI's footprint_costs(..., unknown_as=0)
    px, py, pyaw = x[:, ::2, None], y[:, ::2, None], yaw[:, ::2, None]
    c, s = jnp.cos(pyaw), jnp.sin(pyaw)
    wx = px + c * outline[:, 0] - s * outline[:, 1]
    wy = py + s * outline[:, 0] + c * outline[:, 1]
    mx = jnp.floor((wx - origin[0]) / resolution).astype(jnp.int32)
    my = jnp.floor((wy - origin[1]) / resolution).astype(jnp.int32)
    rows, cols = grid.shape
    inside = (mx >= 0) & (my >= 0) & (mx < cols) & (my < rows)
    costs = grid[jnp.clip(my, 0, rows - 1), jnp.clip(mx, 0, cols - 1)]
    costs = jnp.where(inside & (costs != Costmap.NO_INFORMATION), costs, 0)
    worst = costs.max(axis=-1).astype(jnp.float32)
    collision = (worst >= Costmap.INSCRIBED).any(axis=1)
    obstacle = (worst / 252.0).mean(axis=1)

    total = (
        w_path * path_cost
        + w_progress * progress
        + w_obstacle * obstacle
        + w_collision * collision
        + temperature * gamma * jnp.einsum("tc,ktc->k", optimal / sigma**2, noise)
    )
    weights = jax.nn.softmax(-(total - total.min()) / temperature)
    optimal = optimal + jnp.einsum("k,ktc->tc", weights, noise)
    command = optimal[0]
    shifted = jnp.concatenate([optimal[1:], optimal[-1:]], axis=0)
    return key, shifted, command


class MPPIJax(MPPI):
    """``MPPI`` with the optimisation in JAX. Parameters: those of ``MPPI``. Debug output:
    ``local_plan`` (the rollouts stay on the device)."""

    debug_outputs: ClassVar[dict[str, str]] = {"local_plan": "nav_msgs/msg/Path"}

    def configure(self) -> None:
        super().configure()
        self._key = jax.random.PRNGKey(self.seed)
        self._clear_optimum()
        self._grid_version: int | None = None
        self._upload_costmap()
        # Compile now (configure may take seconds; a control cycle may not).
        state = np.zeros(3)
        path = np.column_stack([np.linspace(0.0, 1.0, 5), np.zeros(5)])
        self._optimise(state, path)
        self._key = jax.random.PRNGKey(self.seed)  # the warm-up leaves no trace
        self._clear_optimum()
        self.logger.info("MPPI in JAX on %s", jax.devices()[0])

    def _clear_optimum(self) -> None:
        self._optimal: Any = jnp.zeros((self.time_steps, 2), jnp.float32)

    def _upload_costmap(self) -> None:
        costmap = self.costmap
        if self._grid_version == costmap.version and self.outline is not None:
            return
        self._grid = jnp.asarray(costmap.data)
        self._origin = jnp.asarray([costmap.origin_x, costmap.origin_y], jnp.float32)
        self.outline = costmap.footprint_outline(spacing=max(costmap.resolution, 0.2))
        self._outline = jnp.asarray(self.outline, jnp.float32)
        self._grid_version = costmap.version

    def _optimise(self, state: np.ndarray, path_xy: np.ndarray) -> tuple[float, float]:
        self._upload_costmap()
        vx_top = limit_speed(self.vx_max, self.speed_limit)
        local = self._local_path(path_xy, vx_top)
        # padded to LOCAL_POINTS with its last point: one compiled shape whatever its length
        padded = np.concatenate([local, np.repeat(local[-1:], LOCAL_POINTS - len(local), 0)])
        settings = jnp.asarray(
            [
                self.model_dt, self.vx_min, vx_top, self.wz_max, self.vx_std, self.wz_std,
                self.temperature, self.gamma, self.w_path, self.w_progress, self.w_obstacle,
                self.w_collision, self.costmap.resolution,
            ],
            jnp.float32,
        )  # fmt: skip
        self._key, self._optimal, command = mppi_step(
            self._key,
            self._optimal,
            jnp.asarray(state, jnp.float32),
            jnp.asarray(padded, jnp.float32),
            self._grid,
            self._origin,
            self._outline,
            settings,
            batch_size=self.batch_size,
        )
        vx, wz = np.asarray(command, dtype=np.float64)
        if self.debug_wanted("local_plan"):  # the optimum before its shift for the warm start
            shifted = np.asarray(self._optimal, dtype=np.float64)
            self._publish_optimal(state, np.vstack([[vx, wz], shifted[:-1]]))
        return float(vx), float(wz)
