"""nav2-pyif-bench mppi's host CPU per cycle counts the CPU of this process's children from
the runner's "driving with" line to their exit, and nothing before it."""

from __future__ import annotations

import logging
import subprocess
import sys

import pytest
from nav2_pyif_bench.mppi_bench import host_cpu

pytestmark = pytest.mark.integration

# a child that burns 0.6 s of CPU, says so, sleeps 1 s, then burns 0.6 s more
BURN = (
    "import time\n"
    "def burn(s):\n"
    "    end = time.process_time() + s\n"
    "    while time.process_time() < end: pass\n"
    "burn(0.6); print('asleep', flush=True); time.sleep(1.0); burn(0.6)\n"
)


def test_host_cpu_counts_children_from_driving_on() -> None:
    with host_cpu() as cpu:
        child = subprocess.Popen([sys.executable, "-c", BURN], stdout=subprocess.PIPE, text=True)
        try:
            assert child.stdout is not None and child.stdout.readline() == "asleep\n"
            logging.getLogger("nav2_pyif.runner").info("plan of 1 m by x; driving with y")
            child.wait(timeout=30)
        finally:
            if child.poll() is None:
                child.kill()
                child.wait()
    # the second burn only (its last 50 ms may fall after the last sample)
    assert 0.4 < cpu["cpu_s"] < 0.8, cpu
