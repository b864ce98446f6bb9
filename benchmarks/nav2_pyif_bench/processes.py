"""Start and stop the benchmark's peer processes (planner host, bare queryable, rclpy node)."""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager

from nav2_pyif.common.host_process import free_port
from nav2_pyif.common.signals import deferred

__all__ = ["free_port", "peer_processes", "ros_localhost_env"]


def ros_localhost_env() -> dict[str, str]:
    """Keep DDS on this machine and away from other ROS graphs."""
    return {
        "ROS_DOMAIN_ID": str(random.randint(120, 200)),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
    }


@contextmanager
def peer_processes(commands: dict[str, list[str]], env: dict[str, str]) -> Iterator[None]:
    """Run each command; SIGTERM (then SIGKILL) them all on exit."""
    procs: list[subprocess.Popen[bytes]] = []
    try:
        for command in commands.values():
            with deferred():  # a signal must not come between starting and recording it
                procs.append(
                    subprocess.Popen(
                        [sys.executable, *command],
                        env=dict(os.environ, **env),
                        stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL,
                    )
                )
        yield
    finally:
        for proc in procs:
            if proc.poll() is None:
                proc.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + 5
        for proc in procs:
            try:
                proc.wait(max(0.1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
