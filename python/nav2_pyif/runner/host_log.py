"""The log of the planner host a run starts: its planners' own lines shown as they come, the
whole of it kept with the run's result."""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import TextIO

from nav2_pyif.common.planner_output import PlannerLines


class HostLogFollower:
    """Follows a host's log file on a thread and writes to ``out`` each line ``keep`` picks
    (by default: the planners' print and logger output), until ``stop``."""

    def __init__(
        self,
        path: Path,
        keys: list[str],
        out: TextIO | None = None,
        keep: Callable[[str], bool] | None = None,
        period: float = 0.1,
    ) -> None:
        self.path = path
        self.out = out
        self.keep = keep or PlannerLines(keys)
        self.period = period
        self._offset = 0
        self._partial = b""
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="host-log", daemon=True)

    def start(self) -> HostLogFollower:
        self._thread.start()
        return self

    def stop(self) -> None:
        """Show what is left, then stop following."""
        self._stop.set()
        self._thread.join(5.0)
        self._poll(final=True)

    def _run(self) -> None:
        while not self._stop.wait(self.period):
            self._poll()

    def _poll(self, final: bool = False) -> None:
        try:
            with open(self.path, "rb") as f:
                f.seek(self._offset)
                data = f.read()
        except OSError:
            return
        self._offset += len(data)
        lines = (self._partial + data).split(b"\n")
        self._partial = b"" if final else lines.pop()  # a line still being written
        out = self.out or sys.stderr  # looked up late: pytest swaps sys.stderr per test
        shown = [t for t in (b.decode("utf-8", "replace") for b in lines) if t and self.keep(t)]
        if shown:
            out.write("".join(f"{line}\n" for line in shown))
            out.flush()
