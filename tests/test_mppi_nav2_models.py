"""Nav2MPPI's motion model (mppi_nav2/models.py) against a plain NumPy transcription of Nav2
Jazzy's MotionModel::predict and Optimizer::integrateStateVelocities, rollout by rollout and
step by step: the acceleration limits, the velocities each rollout moves with, its poses."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytestmark = pytest.mark.unit

jax = pytest.importorskip("jax", reason="JAX is not installed (nav2-pyif-planners[jax])")
jnp = jax.numpy

from nav2_pyif_planners.mppi_nav2.models import Controls, roll_out, running_sum  # noqa: E402

from tests.test_mppi_nav2 import settings  # noqa: E402


def nav2_predict(
    cv: np.ndarray, speed: np.ndarray, pose: np.ndarray, s: Any
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nav2's loops over (batch, T, axis) float64: the clamped controls, the velocities
    (the robot's speed first) and the poses (x, y, yaw) after each step."""
    dt = s.model_dt
    batch, steps, _ = cv.shape
    cv = cv.copy()
    v = np.zeros_like(cv)
    v[:, 0] = speed
    for j in range(batch):
        for i in range(1, steps):
            for axis, (low, high) in ((0, (s.ax_min, s.ax_max)), (1, (s.ay_min, s.ay_max))):
                if axis == 1 and not s.holonomic:
                    continue
                last = v[j, i - 1, axis]
                if last > 0:
                    bounds = (last + dt * low, last + dt * high)
                else:
                    bounds = (last - dt * high, last - dt * low)
                cv[j, i - 1, axis] = np.clip(cv[j, i - 1, axis], *bounds)
                v[j, i, axis] = cv[j, i - 1, axis]
            last = v[j, i - 1, 2]
            cv[j, i - 1, 2] = np.clip(cv[j, i - 1, 2], last - dt * s.az_max, last + dt * s.az_max)
            v[j, i, 2] = cv[j, i - 1, 2]
    if not s.holonomic:
        v[:, :, 1] = 0.0
        cv[:, :, 1] = 0.0
    yaw = pose[2] + np.cumsum(v[:, :, 2] * dt, axis=1)
    before = np.concatenate([np.full((batch, 1), pose[2]), yaw[:, :-1]], axis=1)
    dx = v[:, :, 0] * np.cos(before) - v[:, :, 1] * np.sin(before)
    dy = v[:, :, 0] * np.sin(before) + v[:, :, 1] * np.cos(before)
    x = pose[0] + np.cumsum(dx * dt, axis=1)
    y = pose[1] + np.cumsum(dy * dt, axis=1)
    return cv, v, np.stack([x, y, yaw], axis=2)


@pytest.mark.parametrize("model", ["DiffDrive", "Omni"])
def test_roll_out_limits_and_integrates_as_nav2_does(model: str) -> None:
    s = settings(motion_model=model)
    rng = np.random.default_rng(7)
    batch, steps = 200, s.time_steps
    # wide noise and a moving, turning robot: most steps hit an acceleration limit
    cv = rng.normal(0.0, 0.6, (batch, steps, 3)).astype(np.float32)
    speed = np.array([0.3, -0.1 if s.holonomic else 0.0, 0.4], np.float32)
    pose = np.array([1.0, -2.0, 2.9], np.float32)
    controls = Controls(*(jnp.asarray(cv[:, :, a].T) for a in range(3)))
    r = roll_out(controls, tuple(speed), tuple(pose), s)

    want_cv, want_v, want_pose = nav2_predict(cv.astype(np.float64), speed, pose, s)
    for a, got in enumerate(r.controls):
        np.testing.assert_allclose(np.asarray(got).T, want_cv[:, :, a], atol=1e-5)
    for a, got in enumerate(r.velocities):
        np.testing.assert_allclose(np.asarray(got).T, want_v[:, :, a], atol=1e-5)
    for a, got in enumerate((r.x, r.y, r.yaw)):
        np.testing.assert_allclose(np.asarray(got).T, want_pose[:, :, a], atol=2e-4)
    np.testing.assert_allclose(np.asarray(r.cos), np.cos(np.asarray(r.yaw)), atol=1e-5)
    np.testing.assert_allclose(np.asarray(r.sin), np.sin(np.asarray(r.yaw)), atol=1e-5)
    # the limits did bind: the clamped controls differ from the sampled ones
    assert np.abs(want_cv - cv).max() > 0.1


@pytest.mark.parametrize("dtype", [np.float32, np.int32])
def test_running_sum_adds_in_order_from_its_start(dtype: type) -> None:
    steps: np.ndarray = np.random.default_rng(3).integers(-5, 9, (56, 40)).astype(dtype)
    got = np.asarray(jax.jit(running_sum)(jnp.asarray(steps), 3))
    np.testing.assert_array_equal(got, 3 + np.cumsum(steps, axis=0))
    assert got.dtype == dtype
