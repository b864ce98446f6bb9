"""``planner-host --respawn``: a keeper that runs the host as its child and starts it again
whenever it exits, after a back-off (1 s, doubling to 30 s; back to 1 s after a run of 10 s).

The Nav2 plugin starts its local host so: the plugin only starts and stops one process, the
restarts are here. The child stays in the keeper's process group (a signal to the group, as
the plugin's clean-up sends, reaches both) and gets SIGTERM if the keeper dies (Linux), so a
killed keeper leaves no host behind; the keeper gets SIGTERM when the plugin that started it
dies (``--parent-pid``). SIGINT, SIGTERM or SIGHUP to the keeper: SIGTERM to the child,
SIGKILL after a grace, exit 128 + the signal's number.
"""

from __future__ import annotations

import ctypes
import logging
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Sequence

from nav2_pyif.common.signals import Interrupted, deferred, raise_on_signals

log = logging.getLogger("nav2_pyif.server.respawn")
PR_SET_PDEATHSIG = 1  # <sys/prctl.h>


def _die_with(parent: int) -> Callable[[], None]:
    """The child's pre-exec step: SIGTERM when ``parent`` dies, and no start if it already
    has. Safe in preexec_fn: the keeper runs no threads."""
    libc = ctypes.CDLL(None, use_errno=True)

    def preexec() -> None:
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
        if os.getppid() != parent:
            os._exit(1)

    return preexec


def _bind_to_starter(parent: int | None) -> None:
    """SIGTERM to this keeper when ``parent`` (the Nav2 plugin that started it) dies, and an
    exit now if it is gone already (Linux)."""
    if parent is not None and sys.platform == "linux":
        _die_with(parent)()


def describe(returncode: int) -> str:
    """A Popen return code as the log says it: "exited with status 3", "killed by signal 9
    (SIGKILL)"."""
    if returncode >= 0:
        return f"exited with status {returncode}"
    try:
        name = f" ({signal.Signals(-returncode).name})"
    except ValueError:
        name = ""
    return f"killed by signal {-returncode}{name}"


def stop(child: subprocess.Popen[bytes], grace: float) -> None:
    """SIGTERM, then SIGKILL if it still runs after ``grace`` seconds; reaped either way."""
    if child.poll() is None:
        child.terminate()
        try:
            child.wait(grace)
        except subprocess.TimeoutExpired:
            log.warning("planner host (pid %d) ignored SIGTERM; killing it", child.pid)
            child.kill()
            child.wait()


def keep(
    command: Sequence[str],
    *,
    parent: int | None = None,
    first_delay: float = 1.0,
    max_delay: float = 30.0,
    stable_after: float = 10.0,
    grace: float = 5.0,
) -> int:
    """Run ``command`` until a terminating signal, restarting it whenever it exits; returns
    the signal's exit code. ``parent``: the process this keeper ends with."""
    raise_on_signals()
    _bind_to_starter(parent)
    preexec = _die_with(os.getpid()) if sys.platform == "linux" else None
    delay, child = first_delay, None
    try:
        while True:
            with deferred():  # a signal now waits until the child is recorded, to be stopped
                # unbuffered: the host's lines reach the plugin's log as they are written
                child = subprocess.Popen(
                    command, preexec_fn=preexec, env={**os.environ, "PYTHONUNBUFFERED": "1"}
                )
            log.info("planner host started (pid %d): %s", child.pid, " ".join(command))
            started = time.monotonic()
            returncode = child.wait()
            if time.monotonic() - started >= stable_after:
                delay = first_delay
            log.error(
                "planner host (pid %d) %s; restarting in %.1f s",
                child.pid,
                describe(returncode),
                delay,
            )
            time.sleep(delay)
            delay = min(delay * 2, max_delay)
    except Interrupted as stopped:
        log.info("received %s, stopping the planner host", stopped.name)
        if child is not None:
            stop(child, grace)
        return stopped.exit_code
