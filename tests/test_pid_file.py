"""``planner-host --pid-file``: how README's SIGHUP example reaches the host the user started
and no other (it used to send SIGHUP by name, to every planner-host on the machine)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import wait_until

pytestmark = pytest.mark.integration


def test_the_pid_file_names_this_host_once_it_serves_and_goes_with_it(
    tmp_path: Path, start_host: Any
) -> None:
    pid_file = tmp_path / "planner-host.pid"
    host = start_host(
        "--key", "nav2_pyif/pidfile/FollowPath", "--planner", "echo_planners:EchoController",
        "--pid-file", str(pid_file),
    )  # fmt: skip
    assert wait_until(lambda: "ready" in host.log() or host.proc.poll() is not None, 60)
    assert wait_until(pid_file.exists, 5), host.log()
    assert pid_file.read_text() == f"{host.proc.pid}\n"

    os.kill(int(pid_file.read_text()), signal.SIGHUP)  # README: kill -HUP "$(cat FILE)"
    assert wait_until(lambda: "SIGHUP: reloading every planner" in host.log(), 30), host.log()
    assert host.proc.poll() is None  # reloaded, not stopped

    host.proc.send_signal(signal.SIGINT)
    assert host.proc.wait(30) == 128 + signal.SIGINT, host.log()
    assert not pid_file.exists()


def test_a_pid_file_in_a_missing_directory_is_a_usage_error(tmp_path: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.server.cli", "--key", "nav2_pyif/p/FollowPath",
         "--planner", "m:C", "--pid-file", str(tmp_path / "nowhere" / "host.pid")],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert done.returncode == 2
    assert "--pid-file" in done.stderr and "missing or not writable" in done.stderr
