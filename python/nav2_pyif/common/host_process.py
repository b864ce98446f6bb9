"""Start a planner host as a child process (what the offline runner and the testing helpers
use): the same ``planner-host`` a robot runs, listening on a free loopback port."""

from __future__ import annotations

import os
import random
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import yaml

from nav2_pyif.common.signals import deferred


def _ephemeral_start() -> int:
    try:
        return int(Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return 32768  # Linux's default when the range cannot be read


def free_port() -> int:
    """A loopback TCP port that is free now, drawn below the kernel's ephemeral range: a port
    the kernel hands out itself (a Zenoh peer listening on port 0, any outgoing connection) could
    be taken by another process between this choice and the child's bind, one below it only by
    a process that names it."""
    low, high = 20000, _ephemeral_start() - 1
    for _ in range(100):
        # a kernel range starting at or below 20000 leaves none below it: any free port
        port = random.randint(low, high) if high > low else 0
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return int(s.getsockname()[1])
    raise RuntimeError(f"no free TCP port on 127.0.0.1 in {low}..{high}")


class HostExited(RuntimeError):
    """The planner host ended before it served; ``exit_code`` 2 is its usage error (an
    unknown planner, a bad option), which the command that started it reports as its own."""

    def __init__(self, exit_code: int, log: str) -> None:
        super().__init__(f"planner host exited with code {exit_code}:\n{log}")
        self.exit_code = exit_code


class PlannerHostProcess:
    """A ``planner-host`` child process listening on ``endpoint``.

    ``planners``: a list of {key, planner} or {key, module, delegates} entries (written to a
    YAML file for ``--config``); ``args``: further command-line arguments (e.g. ``--serve``);
    ``env``: variables added to this process's environment; ``bound``: the host ends with this
    process (``--parent-pid``), and removes the temporary directory if this process cannot.
    Start a bound host from a thread that outlives it: Linux signals the host when the thread
    that started it ends."""

    def __init__(
        self,
        planners: list[dict[str, Any]] | None = None,
        *,
        args: list[str] | None = None,
        port: int | None = None,
        log_level: str = "WARNING",
        extra_path: list[str] | None = None,
        log_path: Path | None = None,
        env: dict[str, str] | None = None,
        bound: bool = False,
    ) -> None:
        self.planners = planners or []
        self.bound = bound
        self.port = port or free_port()
        self.log_level = log_level
        self.extra_path = extra_path or []
        self.proc: subprocess.Popen[bytes] | None = None
        self.args: list[str] = list(args or [])
        self.env = env or {}
        self._dir = tempfile.TemporaryDirectory(prefix="nav2_pyif_host_")
        self.log_path = log_path or Path(self._dir.name) / "host.log"

    @property
    def endpoint(self) -> str:
        return f"tcp/127.0.0.1:{self.port}"

    def start(self) -> PlannerHostProcess:
        command = [sys.executable, "-m", "nav2_pyif.server.cli", "--listen", self.endpoint]
        if self.planners:
            config = Path(self._dir.name) / "planners.yaml"
            config.write_text(yaml.safe_dump({"planners": self.planners}))
            command += ["--config", str(config)]
        command += ["--log-level", self.log_level]
        for directory in self.extra_path:
            command += ["--path", directory]
        if self.bound:  # killed outright, this process leaves no host nor directory behind
            command += ["--parent-pid", str(os.getpid()), "--parent-tmpdir", self._dir.name]
        command += self.args
        # A signal between the fork and the assignment would leave a host no one stops.
        with open(self.log_path, "ab") as log, deferred():
            self.proc = subprocess.Popen(
                command, stdout=log, stderr=subprocess.STDOUT, env={**os.environ, **self.env}
            )
        return self

    def check_alive(self) -> None:
        """Raise with the host's own words when it has exited (e.g. an unknown planner)."""
        if self.proc is not None and self.proc.poll() is not None:
            raise HostExited(self.proc.returncode, self.log().strip())

    def log(self) -> str:
        return self.log_path.read_text(errors="replace") if self.log_path.exists() else ""

    def stop(self, timeout: float = 10.0) -> int | None:
        """SIGTERM, then SIGKILL after ``timeout``; returns the exit code (143: a clean stop
        on SIGTERM, as ``planner-host`` ends on a signal)."""
        if self.proc is None:
            return None
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        return self.proc.returncode

    def kill(self) -> None:
        """SIGKILL, as a crash would: nothing is saved."""
        if self.proc is not None:
            self.proc.kill()
            self.proc.wait(10)

    def close(self) -> None:
        """Stop the host and remove its temporary directory (config, log)."""
        self.stop()
        self._dir.cleanup()

    def __enter__(self) -> PlannerHostProcess:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.close()


def wait_alive(host: PlannerHostProcess, ready: Any, timeout: float = 30.0) -> None:
    """Wait for ``ready()`` (e.g. a client's wait_for_host) while checking the process."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        host.check_alive()
        if ready(0.2):
            return
    raise TimeoutError(f"planner host did not come up within {timeout:.0f} s:\n{host.log()}")
