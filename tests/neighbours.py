"""Processes the suite did not start, as on a robot computer where it runs beside others: a
Zenoh router on rmw_zenoh's port 7447 (when that port is free and the documented commands,
which use it, can run in a network of their own) and a planner host serving a reference
planner on the key the documents use, in a process group of its own. Started before the first
test (tests/conftest.py), checked after the last (tests/test_foreign_processes.py): alive,
never signalled, never reloaded."""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import time
from pathlib import Path

from nav2_pyif.common.host_process import free_port

from tests.private_network import ZENOH_DEFAULT_PORT, PrivateNetwork, port_is_free

KEY = "nav2_pyif/robot1/FollowPath"  # README's key: a leak into the neighbour would show
PLANNER = "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"
#: what the host logs when it gets a signal (planner-host's own handlers), when one of its
#: workers dies of one, or when it is reloaded
TOUCHED = re.compile(r"\bSIG[A-Z]{2,}\b|(?i:reload)|now serving")


def _start(argv: list[str], log: Path) -> subprocess.Popen[bytes]:
    with open(log, "wb") as out:
        return subprocess.Popen(
            argv,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,  # their own process group, as another user's would be
        )


def _wait_for(proc: subprocess.Popen[bytes], log: Path, words: str, timeout: float) -> str:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        if words in log.read_text(errors="replace"):
            return ""
        time.sleep(0.05)
    return f"{log.name}: no {words!r} after {timeout:.0f} s:\n{log.read_text(errors='replace')}"


def _disturbed(proc: subprocess.Popen[bytes]) -> list[str]:
    """How ``proc`` shows it was signalled: ended, stopped, or signals pending."""
    if proc.poll() is not None:
        return [f"exited with {proc.returncode}"]
    lines = Path(f"/proc/{proc.pid}/status").read_text().splitlines()
    status = {name: value.strip() for name, _, value in (line.partition(":") for line in lines)}
    found = [f"is {status['State']}"] if status["State"][0] in "TtZ" else []
    found += [
        f"has signals pending ({field} {status[field]})"
        for field in ("SigPnd", "ShdPnd")
        if int(status[field], 16)
    ]
    return found


def _command(name: str, module: str) -> list[str]:
    """The console script ``name`` of this venv, so that the process is named as a user's
    is (what a signal sent by name would pick), else ``python -m module``."""
    script = Path(sys.executable).parent / name
    return [str(script)] if script.is_file() else [sys.executable, "-m", module]


class Neighbours:
    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self.router: subprocess.Popen[bytes] | None = None
        self.host: subprocess.Popen[bytes] | None = None
        self.host_log = directory / "foreign-host.log"
        self.router_log = directory / "foreign-router.log"
        self.ready_at = 0  # length of the host's log when it became ready
        self.note = ""  # why no router was started on 7447

    def start(self) -> None:
        tool = _command("nav2-pyif", "nav2_pyif.tools.main")
        isolated = PrivateNetwork()
        why_not = isolated.open()
        isolated.close()
        if why_not is not None:
            self.note = f"no router started on {ZENOH_DEFAULT_PORT}: the docs need it ({why_not})"
        elif not port_is_free(ZENOH_DEFAULT_PORT):
            self.note = f"{ZENOH_DEFAULT_PORT} already taken here: left alone"
        else:
            router = f"tcp/127.0.0.1:{ZENOH_DEFAULT_PORT}"
            self.router = _start([*tool, "router", "--listen", router], self.router_log)
            if _wait_for(self.router, self.router_log, "listening on", 30):
                self.router.wait(10)  # taken meanwhile: carry on without it
                self.note, self.router = f"router on {ZENOH_DEFAULT_PORT} did not start", None
        zenoh = ["--listen", f"tcp/127.0.0.1:{free_port()}"]
        if self.router is not None:
            zenoh += ["--connect", f"tcp/127.0.0.1:{ZENOH_DEFAULT_PORT}"]
        self.host = _start(
            [*_command("planner-host", "nav2_pyif.server.cli"), "--key", KEY, "--planner",
             PLANNER, "--log-level", "INFO", *zenoh],
            self.host_log,
        )  # fmt: skip
        failed = _wait_for(self.host, self.host_log, " ready (", 120)
        assert not failed, failed
        self.ready_at = len(self.host_log.read_text(errors="replace"))

    def problems(self) -> list[str]:
        """What shows that the suite touched the neighbours: exited, stopped, signals pending
        or received, reloads."""
        found = []
        for name, proc in (("foreign planner host", self.host), ("router", self.router)):
            if proc is not None:
                found += [f"the {name} {proc.pid} {what}" for what in _disturbed(proc)]
        since_ready = self.host_log.read_text(errors="replace")[self.ready_at :]
        found += [
            f"the foreign planner host logged: {line}"
            for line in since_ready.splitlines()
            if TOUCHED.search(line)
        ]
        return found

    def stop(self) -> None:
        """SIGINT to the process groups we started, as their owner would stop them."""
        for proc in (self.host, self.router):
            if proc is not None and proc.poll() is None:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(20)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
