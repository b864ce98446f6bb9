"""planner-host --xla-threads N: each planner process starts JAX with N threads in XLA's CPU
pool (XLA names them tf_XLAEigen), whatever the machine's core count."""

from __future__ import annotations

import contextlib
import time
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import process_tree

pytestmark = pytest.mark.integration

pytest.importorskip("jax", reason="JAX is not installed (nav2-pyif-planners[jax])")

PLANNER = ("--key", "xla/threads", "--planner", "jax_started:JaxStartedController")


def thread_names(pid: int) -> list[str]:
    names = []
    for comm in Path(f"/proc/{pid}/task").glob("*/comm"):
        with contextlib.suppress(OSError):  # a thread that ended while we looked
            names.append(comm.read_text().strip())
    return names


def xla_pool_threads(host_pid: int, timeout: float = 60.0) -> int:
    """The tf_XLAEigen threads of the host's worker, once its planner started JAX."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        for pid in process_tree(host_pid):
            if "tf_XLAEigen" in thread_names(pid):
                time.sleep(0.5)  # the pool's threads start together; let the last one show
                return thread_names(pid).count("tf_XLAEigen")
        time.sleep(0.2)
    raise AssertionError(f"no process of host {host_pid} started XLA in {timeout} s")


@pytest.mark.parametrize("threads", [1, 2])
def test_each_planner_process_gets_the_xla_pool_it_was_given(start_host: Any, threads: int) -> None:
    host = start_host(*PLANNER, "--xla-threads", str(threads))
    assert host.proc is not None
    assert xla_pool_threads(host.proc.pid) == threads
