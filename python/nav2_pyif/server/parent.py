"""``planner-host --parent-pid``: a host ends with the process that started it (the Nav2
plugin, ``nav2-pyif sim``), even one killed outright (SIGKILL), and takes that process's
temporary directory for it (``--parent-tmpdir``: its config and log), which no one else would
remove then."""

from __future__ import annotations

import atexit
import ctypes
import os
import shutil
import signal
import sys
from pathlib import Path

PR_SET_PDEATHSIG = 1  # <sys/prctl.h>


def bind_to_parent(parent: int) -> bool:
    """SIGTERM to this process when ``parent`` dies (Linux: the host then stops as on any
    SIGTERM, workers included); False when ``parent`` is gone already."""
    if sys.platform == "linux":
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
    return os.getppid() == parent


def remove_when_orphaned(parent: int, directory: Path) -> None:
    """At exit, remove ``directory`` if ``parent`` is gone: it can no longer do so itself."""

    def remove() -> None:
        if os.getppid() != parent:
            shutil.rmtree(directory, ignore_errors=True)

    atexit.register(remove)
