"""Shared fixtures: real planner-host processes and real Zenoh sessions on loopback."""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import zenoh
from nav2_pyif import Costmap
from nav2_pyif.common.host_process import PlannerHostProcess, free_port
from nav2_pyif.common.zenoh_config import connect_to

from tests.neighbours import Neighbours
from tests.tiers import unit_tier_only

__all__ = ["free_port"]  # tests import it from here

FIXTURES = Path(__file__).parent / "fixtures"
ROOT = Path(__file__).resolve().parents[1]
#: What README's "To use the tools by hand" sources: the project's venv and ROS environment.
ENV_SCRIPT = Path(os.environ.get("NAV2_PYIF_VENV", ROOT / ".venv")) / "nav2_pyif_env.sh"


#: The file whose test checks, after every other test, the processes the suite did not start.
FOREIGN_PROCESSES_TEST = "test_foreign_processes.py"
_NEIGHBOURS = pytest.StashKey["Neighbours"]()


_TERMINATED = pytest.StashKey[bool]()


def pytest_configure(config: pytest.Config) -> None:
    """SIGTERM (a cancelled CI job, ``kill``) ends the run as Ctrl-C does: pytest unwinds, so
    the fixtures' teardown and pytest_sessionfinish stop every process the suite started (the
    neighbours run in sessions of their own: a signal to the suite's group misses them). Then
    pytest_unconfigure dies of the SIGTERM, for its conventional exit status."""

    def interrupted(signum: int, frame: object) -> None:
        config.stash[_TERMINATED] = True
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, interrupted)


def pytest_unconfigure(config: pytest.Config) -> None:
    if config.stash.get(_TERMINATED, False):
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTERM)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The check of the neighbours runs last: after everything that could have touched them."""
    last = [item for item in items if item.path.name == FOREIGN_PROCESSES_TEST]
    items[:] = [item for item in items if item.path.name != FOREIGN_PROCESSES_TEST] + last


def pytest_collection_finish(session: pytest.Session) -> None:
    """With that check collected (the whole suite), start the neighbours before any test."""
    if any(item.path.name == FOREIGN_PROCESSES_TEST for item in session.items):
        directory = Path(tempfile.mkdtemp(prefix="nav2_pyif_neighbours_"))
        neighbours = Neighbours(directory)
        session.config.stash[_NEIGHBOURS] = neighbours
        neighbours.start()


def pytest_sessionfinish(session: pytest.Session) -> None:
    neighbours = session.config.stash.get(_NEIGHBOURS, None)
    if neighbours is not None:
        neighbours.stop()
        shutil.rmtree(neighbours.directory, ignore_errors=True)


def _guarded(item: pytest.Item) -> Iterator[None]:
    """A test marked unit opens no Zenoh session and starts no process (tests/tiers.py): in
    its setup too, where module and session fixtures start, not only in the test itself."""
    if item.get_closest_marker("unit") is None:
        yield
        return
    with unit_tier_only():
        yield


@pytest.hookimpl(wrapper=True)
def pytest_runtest_setup(item: pytest.Item) -> Iterator[None]:
    return (yield from _guarded(item))


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item: pytest.Item) -> Iterator[None]:
    return (yield from _guarded(item))


@pytest.fixture(scope="session")
def neighbours(request: pytest.FixtureRequest) -> Neighbours:
    """The router and planner host running beside the suite (tests/neighbours.py)."""
    return request.config.stash[_NEIGHBOURS]


def in_project_env(command: str) -> list[str]:
    """argv running the shell ``command`` as a user would, with ENV_SCRIPT sourced."""
    return ["bash", "-c", f"source {ENV_SCRIPT}\n{command}"]


#: nav2_core exception names (Jazzy+), as the planner API must offer them
CONTROLLER_ERRORS = [
    "ControllerException",
    "InvalidController",
    "ControllerTFError",
    "FailedToMakeProgress",
    "PatienceExceeded",
    "InvalidPath",
    "NoValidControl",
    "ControllerTimedOut",
]
PLANNER_ERRORS = [
    "PlannerException",
    "InvalidPlanner",
    "StartOccupied",
    "GoalOccupied",
    "StartOutsideMapBounds",
    "GoalOutsideMapBounds",
    "NoValidPathCouldBeFound",
    "PlannerTimedOut",
    "PlannerTFError",
    "NoViapointsGiven",
    "PlannerCancelled",
]


def host_process(port: int, args: list[str], log_path: Path) -> PlannerHostProcess:
    """A ``planner-host`` on a loopback port, the test fixtures importable, logging at INFO."""
    return PlannerHostProcess(
        args=args,
        port=port,
        log_level="INFO",
        log_path=log_path,
        env={"PYTHONPATH": os.pathsep.join([str(FIXTURES), os.environ.get("PYTHONPATH", "")])},
    )


@pytest.fixture
def start_host(tmp_path: Path) -> Iterator[object]:
    hosts: list[PlannerHostProcess] = []

    def start(*args: str, port: int | None = None) -> PlannerHostProcess:
        host = host_process(port or free_port(), list(args), tmp_path / f"host{len(hosts)}.log")
        hosts.append(host.start())
        return host

    yield start
    for host in hosts:
        if host.proc is not None and host.proc.poll() is None:
            host.kill()


def open_client_session(endpoint: str, mode: str = "peer") -> zenoh.Session:
    return connect_to([endpoint], mode)


@pytest.fixture
def zsession_factory() -> Iterator[object]:
    sessions: list[zenoh.Session] = []

    def make(endpoint: str, mode: str = "peer") -> zenoh.Session:
        sessions.append(open_client_session(endpoint, mode))
        return sessions[-1]

    yield make
    for session in sessions:
        session.close()


def configure_body(plugin_type: str = "controller", **fields: Any) -> dict[str, Any]:
    """A configure request's body as controller_server's FollowPath sends it (its costmap:
    make_costmap()); ``fields`` replace or add fields."""
    body: dict[str, Any] = {
        "plugin_type": plugin_type,
        "name": "FollowPath",
        "node": "controller_server",
        "params": {},
        "global_frame": "odom",
        "robot_base_frame": "base_link",
        "costmap": make_costmap().to_wire(),
    }
    return body | fields


def make_costmap(size: int = 40, version: int = 1, frame: str = "odom") -> Costmap:
    grid = np.zeros((size, size), np.uint8)
    grid[size // 2 :, size // 2 :] = Costmap.LETHAL
    return Costmap(
        grid,
        0.1,
        origin_x=0.0,
        origin_y=0.0,
        frame_id=frame,
        version=version,
        footprint=[[0.2, 0.1], [0.2, -0.1], [-0.2, -0.1], [-0.2, 0.1]],
    )


def _stat(pid: int | str) -> list[str]:
    """/proc/PID/stat's fields after the command name: state, ppid, ..., start time [19]."""
    return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()


def _parents() -> dict[int, int]:
    """pid -> parent pid of every process now, from /proc."""
    parents: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        with contextlib.suppress(OSError, ValueError):
            parents[int(entry.name)] = int(_stat(entry.name)[1])
    return parents


def child_pids(parent: int) -> list[int]:
    """``parent``'s children now: what a test signals, never a process name."""
    return [pid for pid, pp in _parents().items() if pp == parent]


def process_tree(root: int) -> dict[int, tuple[str, str]]:
    """``root``'s descendants now: pid -> (start time, command line), from /proc."""
    parents = _parents()
    found: dict[int, tuple[str, str]] = {}
    frontier = [root]
    while frontier:
        parent = frontier.pop()
        for pid in [p for p, pp in parents.items() if pp == parent]:
            with contextlib.suppress(OSError):
                command = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ")
                found[pid] = (_stat(pid)[19], command.decode(errors="replace"))
                frontier.append(pid)
    return found


def survivors(tree: dict[int, tuple[str, str]]) -> dict[int, str]:
    """The processes of a ``process_tree`` still running (same pid and start time)."""
    alive = {}
    for pid, (started, command) in tree.items():
        with contextlib.suppress(OSError):
            fields = _stat(pid)
            if fields[19] == started and fields[0] != "Z":
                alive[pid] = command
    return alive


def nav2_pyif_tool(*args: str, timeout: float = 90) -> subprocess.CompletedProcess[str]:
    """``nav2-pyif ARGS`` (this Python's), its output captured."""
    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def wait_until(predicate: object, timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():  # type: ignore[operator]
            return True
        time.sleep(0.01)
    return False


def worker_pid_in(log: str, key: str) -> int | None:
    """The pid of the worker serving ``key``, newest first, from a planner host's log: its
    "serving <planner> on <key>/** (<type>, worker <pid>)" line at start and after a swap,
    and "<key>: worker <pid> restarted" after a restart."""
    serving = re.compile(rf" on {re.escape(key)}/\*\* \([\w]+, worker (\d+)\)")
    restarted = re.compile(rf"{re.escape(key)}: worker (\d+) restarted")
    for line in reversed(log.splitlines()):
        found = serving.search(line) or restarted.search(line)
        if found:
            return int(found.group(1))
    return None
