"""``--xla-threads``: the size of XLA's CPU thread pool in the processes that run planners.

XLA (JAX's compiler) splits a compiled step's kernels over a pool with a thread per core. On a
small robot computer the other cores are busy with Nav2, so the split step waits for them and
costs more CPU. With one thread, a step's kernels run one after another on one core, as Nav2's
own controllers run: Nav2MPPI's 1000 x 56 cycle took 0.14 ms less in Nav2's controller_server
on a 2-core VM (BENCHMARKS.md, "One XLA thread"). XLA reads the size from the environment when
JAX starts, so the host sets it before any planner is imported; worker processes inherit it."""

from __future__ import annotations

import argparse
import logging
import os

from nav2_pyif.common.option_types import positive_int

#: the variables XLA's CPU client reads for its thread pool's size, first found wins
#: (DefaultThreadPoolSize, xla/pjrt/utils.cc): PJRT_NPROC, and NPROC, all that older XLAs read
VARIABLES = ("PJRT_NPROC", "NPROC")


def add_xla_threads_argument(group: argparse._ArgumentGroup) -> None:
    group.add_argument(
        "--xla-threads",
        type=positive_int,
        metavar="N",
        help="threads in XLA's CPU pool in each planner process (JAX planners on a CPU), "
        "> 0; 1 runs each step on one core, faster for a lone robot on a small computer "
        "shared with Nav2 (default: XLA's, one per core)",
    )


def apply_xla_threads(threads: int | None, log: logging.Logger) -> None:
    """Set XLA's pool size for this process and the workers it starts, before JAX starts."""
    if threads is None:
        return
    for variable in VARIABLES:
        os.environ[variable] = str(threads)
    log.info("--xla-threads: XLA's CPU pool has %d thread(s) in each planner process", threads)
