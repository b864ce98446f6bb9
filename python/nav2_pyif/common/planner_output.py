"""A planner's own output in a host's log: what marks it, and how to find it again.

A planner host's log holds the host's lines and, interleaved, each planner's: its
``self.logger`` records (logger ``nav2_pyif.planner.<plugin name>``) and its ``print`` output,
which the worker prefixes with ``[<key>] ``. The offline runner, whose host logs to a file,
picks these lines out and shows them (``planner_lines``).
"""

from __future__ import annotations

import re
from typing import Any, TextIO

#: The logger a planner's ``self.logger`` is a child of.
PLANNER_LOGGER = "nav2_pyif.planner"
# A log record of a planner's logger (the host's and the worker's formats both end with
# "[LEVEL] ... [logger] message").
_PLANNER_RECORD = re.compile(r"^\[[^\]]*\] \[[A-Z]+\] .*?\[" + re.escape(PLANNER_LOGGER) + r"\.")
_RECORD = re.compile(r"^\[[^\]]*\] \[[A-Z]+\] ")


def print_marker(key: str) -> str:
    return f"[{key}] "


class MarkedStream:
    """A text stream that starts each line with ``marker`` and flushes at each line end (a
    crash loses no finished line)."""

    def __init__(self, stream: TextIO, marker: str) -> None:
        self._stream = stream
        self._marker = marker
        self._line_start = True

    def write(self, text: str) -> int:
        for piece in text.splitlines(keepends=True):
            if self._line_start:
                self._stream.write(self._marker)
            self._stream.write(piece)
            self._line_start = piece.endswith(("\n", "\r"))
        if text.endswith("\n"):
            self._stream.flush()
        return len(text)

    def __getattr__(self, name: str) -> Any:  # flush, fileno, isatty, encoding, ...
        return getattr(self._stream, name)


class PlannerLines:
    """Fed a host's log line by line, keeps the planners' own: print output marked with one of
    ``keys`` and the records of planner loggers with their continuation lines (a logged
    traceback)."""

    def __init__(self, keys: list[str]) -> None:
        self._markers = tuple(print_marker(key) for key in keys)
        self._in_record = False

    def __call__(self, line: str) -> bool:
        if _RECORD.match(line):
            self._in_record = bool(_PLANNER_RECORD.match(line))
            return self._in_record
        if line.startswith(self._markers):
            self._in_record = False
            return True
        return self._in_record  # a record's continuation line
