"""Where a worker crashed or hangs: its Python stack, written to a file its supervisor reads.

A worker that segfaults, calls ``os._exit`` or hangs in native code cannot answer with a
traceback, so it leaves one behind: ``faulthandler`` writes the stack of a fatal signal
(SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL) and, on SIGUSR1, of every thread (what the
supervisor sends to a call that overran its deadline, before it is killed); ``os._exit``
writes its caller's stack first. The supervisor logs the stack and returns it as the
traceback of the errors it answers for that worker.
"""

from __future__ import annotations

import contextlib
import faulthandler
import os
import signal
import sys
import tempfile
import time
import traceback
from pathlib import Path
from typing import IO, NoReturn

#: What the supervisor sends a worker to dump every thread's stack (faulthandler).
DUMP_SIGNAL = signal.SIGUSR1
_SERVER_DIR = str(Path(__file__).resolve().parent)
_real_exit = os._exit  # nav2_pyif's own exits (host gone) leave no stack


def real_exit(code: int) -> NoReturn:
    _real_exit(code)


def install(path: str) -> IO[str]:
    """In the worker, before the planner is imported: stacks go to ``path``. Returns the file,
    which must stay open for the worker's life."""
    out = open(path, "a", encoding="utf-8", buffering=1)  # noqa: SIM115 (kept open on purpose)
    # Both ends hold it open now: the name can go at once, not only after the planner loaded
    # (a host killed while a slow planner imports would leave the file behind).
    with contextlib.suppress(OSError):
        os.unlink(path)
    faulthandler.enable(file=out, all_threads=True)
    faulthandler.register(DUMP_SIGNAL, file=out, all_threads=True, chain=False)

    def exit_with_stack(status: int) -> NoReturn:
        frames = traceback.extract_stack(sys._getframe(1))
        out.write(f"Planner called os._exit({status}) (most recent call last):\n")
        out.write("".join(traceback.format_list(_planner_frames(frames))))
        out.flush()
        _real_exit(status)

    os._exit = exit_with_stack
    return out


def _planner_frames(frames: traceback.StackSummary) -> list[traceback.FrameSummary]:
    """The frames below the host's dispatch into the planner: the planner's own first."""
    last_server = max(
        (i for i, f in enumerate(frames) if f.filename.startswith(_SERVER_DIR)), default=-1
    )
    return list(frames[last_server + 1 :]) or list(frames)


def tidy(text: str) -> str:
    """faulthandler's dump without the host's part: the worker's cancel thread, and the
    frames of each thread below the host's call into the planner."""
    blocks = []
    for block in text.split("\n\n"):
        if "in _serve_cancels" in block:
            continue
        lines = block.split("\n")
        cut = next((i for i, line in enumerate(lines) if _SERVER_DIR in line), len(lines))
        blocks.append("\n".join(lines[:cut]))
    return "\n\n".join(blocks)


class StackFile:
    """The supervisor's end: a temporary file the worker writes its stacks to, read through a
    descriptor kept open, so that its name can go as soon as the worker has opened it
    (``unlink``): a host killed with SIGKILL leaves no file behind."""

    def __init__(self) -> None:
        self._fd, self.path = tempfile.mkstemp(prefix="nav2_pyif_worker_", suffix=".stack")
        self._read = 0

    def unlink(self) -> None:
        """The worker has it open (it opens it before loading the planner)."""
        with contextlib.suppress(OSError):
            os.unlink(self.path)

    def read_new(self) -> str:
        """What the worker wrote since the last read ("" when nothing)."""
        chunks = []
        with contextlib.suppress(OSError):
            while chunk := os.pread(self._fd, 65536, self._read):
                chunks.append(chunk)
                self._read += len(chunk)
        return tidy(b"".join(chunks).decode("utf-8", errors="replace"))

    def dump(self, pid: int, timeout: float = 1.0) -> str:
        """Ask a live worker for every thread's stack; wait until it is written (its size
        stops changing), at most ``timeout`` s."""
        try:
            os.kill(pid, DUMP_SIGNAL)
        except OSError:
            return self.read_new()
        deadline, size = time.monotonic() + timeout, -1
        while time.monotonic() < deadline:
            time.sleep(0.01)
            now = self._size()
            if now > self._read and now == size:
                break
            size = now
        return self.read_new()

    def _size(self) -> int:
        try:
            return os.fstat(self._fd).st_size
        except OSError:
            return 0

    def remove(self) -> None:
        """Once only: a descriptor closed twice could be another file's by then."""
        self.unlink()
        if self._fd >= 0:
            with contextlib.suppress(OSError):
                os.close(self._fd)
            self._fd = -1
