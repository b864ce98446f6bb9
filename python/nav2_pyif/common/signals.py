"""Terminating signals for the command-line tools: SIGINT, SIGTERM and SIGHUP become an
``Interrupted`` exception in the main thread, so every ``finally`` (child processes,
temporary files, Zenoh sessions) runs, and the command exits with the conventional code
128 + signal number (130, 143, 129) and no traceback.

Only commands install the handlers (``raise_on_signals``); library code merely lets
``Interrupted`` pass through its clean-up. ``planner-host`` keeps its own handlers: SIGHUP
reloads its planners there.
"""

from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterator
from types import FrameType

TERMINATING = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


class Interrupted(BaseException):
    """A terminating signal arrived. A BaseException, as KeyboardInterrupt: ``except
    Exception`` does not swallow it."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum

    @property
    def name(self) -> str:
        return signal.Signals(self.signum).name

    @property
    def exit_code(self) -> int:
        return exit_code(self.signum)


def exit_code(signum: int) -> int:
    """What a shell reports for a command ended by ``signum``."""
    return 128 + signum


class _State:
    received: int | None = None  # the first signal: later ones wait for its clean-up
    deferring = 0
    pending: int | None = None


def _handler(signum: int, _frame: FrameType | None) -> None:
    if _State.received is not None:
        return  # already shutting down: let the clean-up finish
    if _State.deferring:
        _State.pending = signum
        return
    _State.received = signum
    raise Interrupted(signum)


def raise_on_signals() -> None:
    """From now on SIGINT, SIGTERM and SIGHUP raise Interrupted in the main thread (once)."""
    _State.received = _State.pending = None
    for signum in TERMINATING:
        signal.signal(signum, _handler)


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Hold a terminating signal until the block ends, then raise it: for steps that must
    not be cut in two (starting a child process and recording it, so it can be stopped)."""
    _State.deferring += 1
    try:
        yield
    finally:
        _State.deferring -= 1
        if not _State.deferring and _State.pending is not None:
            signum, _State.pending = _State.pending, None
            _handler(signum, None)
