"""Nav2MPPI's lanes (lanes.py): robots take JAX's CPU devices, one per core, in turn, so that
a fleet's steps run side by side; a device count the user chose, or JAX already started in
the process, is left as it is. Each case in a fresh interpreter: JAX fixes its device count
once per process."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.integration

pytest.importorskip("jax", reason="JAX is not installed (nav2-pyif-planners[jax])")

ROOT = Path(__file__).resolve().parents[1]

LANES_PROBE = """
import os
import jax
{before}
from tests.test_mppi_nav2 import controller
robots = [controller(batch_size=64, time_steps=24) for _ in range(4)]
print(len(jax.local_devices()), len(os.sched_getaffinity(0)))
print(*[r.device.id for r in robots])
"""


def lanes_in_a_fresh_process(before: str = "", xla_flags: str = "") -> tuple[int, int, list[int]]:
    """(JAX's CPU devices, this process's cores, each configured robot's device id) in a new
    interpreter: JAX's device count is fixed once per process."""
    env = {**os.environ, "XLA_FLAGS": xla_flags}
    out = subprocess.run(
        [sys.executable, "-c", LANES_PROBE.format(before=before)],
        cwd=ROOT, env=env, capture_output=True, text=True, timeout=300, check=True,
    ).stdout.split("\n")  # fmt: skip
    devices, cores = (int(v) for v in out[-3].split())
    return devices, cores, [int(v) for v in out[-2].split()]


def test_robots_take_a_cpu_device_per_core_in_turn() -> None:
    devices, cores, lanes = lanes_in_a_fresh_process()
    assert devices == cores
    assert lanes == [i % cores for i in range(4)]  # robot i on lane i mod cores


def test_the_users_device_count_and_a_started_jax_are_left_as_they_are() -> None:
    devices, _, lanes = lanes_in_a_fresh_process(
        xla_flags="--xla_force_host_platform_device_count=3"
    )
    assert devices == 3 and lanes == [0, 1, 2, 0]
    devices, _, lanes = lanes_in_a_fresh_process(before="jax.numpy.zeros(1).block_until_ready()")
    assert devices == 1 and lanes == [0, 0, 0, 0]  # JAX started first: its one device kept
