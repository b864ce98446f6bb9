"""The console scripts' entry points (``planner-host``, ``nav2-pyif``, ``nav2-pyif-bench``).

Standard library only, and outside the ``nav2_pyif`` package (whose ``__init__`` imports NumPy
and the ROS messages), so that it runs before the command's modules are imported: about half a
second in which Python's default SIGINT handler would turn a Ctrl-C into a KeyboardInterrupt
traceback and exit code 1. The terminating signals are blocked while the command imports; one
that arrives meanwhile stays pending and is delivered when they are unblocked, before the
command starts: SIGINT ends it with exit code 130 and one line, SIGTERM and SIGHUP by their
default action (143, 129 in the shell). From then on each command handles signals itself
(``nav2_pyif.common.signals``; ``planner-host`` its own handlers).
"""

from __future__ import annotations

import importlib
import signal
import sys
from collections.abc import Callable

TERMINATING = {signal.SIGINT, signal.SIGTERM, signal.SIGHUP}
SIGINT_EXIT = 128 + signal.SIGINT


def _load(target: str) -> Callable[[], int]:
    """``module:function``, imported with the terminating signals held back."""
    module, _, name = target.partition(":")
    signal.pthread_sigmask(signal.SIG_BLOCK, TERMINATING)
    try:
        command: Callable[[], int] = getattr(importlib.import_module(module), name)
    finally:
        # Unblocked even if they came blocked (scripts/sim.sh execs the command so, to cover
        # the interpreter's own start): a pending signal is delivered here.
        signal.pthread_sigmask(signal.SIG_UNBLOCK, TERMINATING)
    return command


ROS_HINT = "source a ROS 2 setup.bash, or pip install the ros extra: 'nav2-pyif[ros]'"
#: Where each third-party module the commands import comes from, for the message when one is
#: missing: a colcon workspace gets all but eclipse-zenoh from rosdep (README, Install).
INSTALL_HINTS = {
    "zenoh": "pip install eclipse-zenoh (no rosdep key has it; in a ROS 2 workspace, into a "
    "venv made with --system-site-packages: README, Install)",
    "msgpack": "pip install msgpack, or apt install python3-msgpack",
    "numpy": "pip install numpy, or apt install python3-numpy",
    "yaml": "pip install pyyaml, or apt install python3-yaml",
    **dict.fromkeys(("rclpy", "geometry_msgs", "nav_msgs", "std_msgs"), ROS_HINT),
    # Not the core's: the runner's extra, the benchmarks' own distribution's.
    "tqdm": "pip install 'nav2-pyif[runner]'",
    "matplotlib": "pip install 'nav2-pyif[runner]' (nav2-pyif-bench: pip install ./benchmarks)",
    "cryptography": "pip install ./benchmarks in a clone (nav2-pyif-bench)",
}


def run(target: str, prog: str) -> int:
    """Run the command ``target`` (``module:function``); 130 if SIGINT comes before it has
    its own handlers; 1, saying how to install it, if a dependency cannot be imported."""
    try:
        return _load(target)()
    except KeyboardInterrupt:
        print(f"{prog}: stopped by SIGINT", file=sys.stderr)
        return SIGINT_EXIT
    except ModuleNotFoundError as exc:
        top = (exc.name or "").split(".")[0]
        if top not in INSTALL_HINTS:
            raise
        print(
            f"{prog}: the Python module {top!r} cannot be imported by {sys.executable}: "
            f"{INSTALL_HINTS[top]}",
            file=sys.stderr,
        )
        return 1


#: Each command's real main, imported once the signals are held.
TARGETS = {
    "planner-host": "nav2_pyif.server.cli:main",
    "nav2-pyif": "nav2_pyif.tools.main:main",
    "nav2-pyif-bench": "nav2_pyif_bench.cli:main",
}


def planner_host() -> int:
    return run(TARGETS["planner-host"], "planner-host")


def nav2_pyif() -> int:
    return run(TARGETS["nav2-pyif"], "nav2-pyif")


def nav2_pyif_bench() -> int:
    return run(TARGETS["nav2-pyif-bench"], "nav2-pyif-bench")
