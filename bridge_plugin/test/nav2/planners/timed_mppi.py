"""The MPPI side-by-side's Python controllers, each timed as Nav2's MPPI times itself: the
controller method alone, logged once per call ("compute: 7.83 ms") for the driver
(test_mppi_side_by_side.py) to read from the host's log, as it reads Nav2's "Control loop
execution time" lines from controller_server's. A batched host's call for a fleet
(``compute_velocity_commands_batch``) is logged whole, with its robot count ("batch compute:
21.40 ms, 10 robots"), for test_mppi_fleet_stacks.py."""

from __future__ import annotations

import logging
import time
from typing import Any

from nav2_pyif_planners.mppi import MPPI
from nav2_pyif_planners.mppi_jax import MPPIJax
from nav2_pyif_planners.mppi_nav2 import Nav2MPPI

LOG = logging.getLogger("timed_mppi")


class _Timed:
    """Times ``compute_velocity_commands`` of the controller class it is mixed into."""

    def compute_velocity_commands(self, *args: Any, **kwargs: Any) -> Any:
        started = time.perf_counter()
        try:
            return super().compute_velocity_commands(*args, **kwargs)  # type: ignore[misc]
        finally:
            LOG.info("compute: %.3f ms", (time.perf_counter() - started) * 1e3)


class TimedNav2MPPI(_Timed, Nav2MPPI):
    @classmethod
    def compute_velocity_commands_batch(cls, batch: Any) -> list[Any]:
        started = time.perf_counter()
        try:
            return super().compute_velocity_commands_batch(batch)
        finally:
            elapsed = (time.perf_counter() - started) * 1e3
            LOG.info("batch compute: %.3f ms, %d robots", elapsed, len(batch))


class TimedMPPIJax(_Timed, MPPIJax):
    pass


class TimedMPPI(_Timed, MPPI):
    pass
