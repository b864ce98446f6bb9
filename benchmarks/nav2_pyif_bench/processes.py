"""Start and stop the benchmark's peer processes (planner host, bare queryable, rclpy node)."""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from nav2_pyif.common.host_process import free_port
from nav2_pyif.common.signals import deferred

__all__ = ["Peers", "free_port", "peer_processes", "ros_localhost_env"]


def ros_localhost_env() -> dict[str, str]:
    """Keep DDS on this machine and away from other ROS graphs."""
    return {
        "ROS_DOMAIN_ID": str(random.randint(120, 200)),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
    }


class Peers:
    """The started peers, each with its log (stdout and stderr), for saying why one that was
    waited for did not come up."""

    def __init__(self, log_dir: str) -> None:
        self.log_dir = Path(log_dir)
        self.procs: dict[str, subprocess.Popen[bytes]] = {}

    def start(self, name: str, command: list[str], env: dict[str, str]) -> None:
        with open(self.log_dir / f"{name}.log", "wb") as log, deferred():
            # a signal must not come between starting and recording it
            self.procs[name] = subprocess.Popen(
                [sys.executable, *command],
                env=dict(os.environ, **env),
                stdout=log,
                stderr=subprocess.STDOUT,
            )

    def not_up(self, what: str) -> RuntimeError:
        """The error for ``what`` not coming up, with the log of every peer that has ended."""
        ended = [
            f"{name} exited with code {proc.returncode}:\n"
            + (self.log_dir / f"{name}.log").read_text(errors="replace")[-2000:]
            for name, proc in self.procs.items()
            if proc.poll() is not None
        ]
        return RuntimeError("\n".join([f"{what} did not come up", *ended]))


@contextmanager
def peer_processes(commands: dict[str, list[str]], env: dict[str, str]) -> Iterator[Peers]:
    """Run each command; SIGTERM (then SIGKILL) them all on exit."""
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_bench_") as log_dir:
        peers = Peers(log_dir)
        try:
            for name, command in commands.items():
                peers.start(name, command, env)
            yield peers
        finally:
            for proc in peers.procs.values():
                if proc.poll() is None:
                    proc.send_signal(signal.SIGTERM)
            deadline = time.monotonic() + 5
            for proc in peers.procs.values():
                try:
                    proc.wait(max(0.1, deadline - time.monotonic()))
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
