"""Where each Nav2MPPI robot's step runs: one XLA device per CPU core ("lanes"), each robot
kept on one of them, taken in turn as robots are configured.

On a CPU, JAX's one device runs dispatched steps one after another, each split over every
core. Splitting a 1000 x 56 step over two cores buys 15 % of its wall time for 40 % more
CPU, and a fleet's steps wait in one queue. With a device per core, two robots' steps run at
once instead: per robot-cycle, less CPU and less wall time (BENCHMARKS.md, "A fleet: a lane
per core"). A GPU backend is left as it is: its devices are the lanes.

JAX fixes its CPU device count when its backend starts, so ``claim_cpu_lanes`` runs when
this package is imported. It leaves the count alone where the user chose one
(``jax_num_cpu_devices``, ``--xla_force_host_platform_device_count``) or where JAX already
started (a planner of another package ran first): then the robots share the devices there
are."""

from __future__ import annotations

import contextlib
import itertools
import os
from typing import Any

import jax

_turn = itertools.count()


def claim_cpu_lanes() -> None:
    """Ask JAX for a CPU device per core this process may run on, if it is not too late and
    nobody chose otherwise."""
    if jax.config.values["jax_num_cpu_devices"] != -1:
        return
    if "xla_force_host_platform_device_count" in os.environ.get("XLA_FLAGS", ""):
        return
    with contextlib.suppress(RuntimeError):  # JAX already started here: its devices stay
        jax.config.update("jax_num_cpu_devices", len(os.sched_getaffinity(0)))


def next_lane() -> Any:
    """The device the next configured robot runs on: the default backend's devices in turn."""
    devices = jax.local_devices()
    return devices[next(_turn) % len(devices)]
