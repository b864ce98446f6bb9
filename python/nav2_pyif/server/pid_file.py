"""``planner-host --pid-file FILE``: the host's process id, for a SIGHUP (reload every planner)
or SIGTERM sent to this host and no other (``kill -HUP "$(cat FILE)"``), never by name.

Written once the host serves (a SIGHUP before that would stop it, not reload it), replaced
atomically, and removed when the host exits if it still holds this host's id.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path


def write_pid_file(path: Path) -> None:
    partial = path.with_name(f".{path.name}.{os.getpid()}")
    partial.write_text(f"{os.getpid()}\n")
    partial.replace(path)  # a reader sees the whole id or the previous file, never half


def remove_pid_file(path: Path) -> None:
    """Remove ``path`` if it names this process (another host may have taken it over)."""
    with contextlib.suppress(OSError, ValueError):
        if int(path.read_text()) == os.getpid():
            path.unlink()
