"""What planner-host and nav2-pyif sim say: in order, once, and true.
Real hosts, real signals (to the process this test started only), real Zenoh sessions."""

from __future__ import annotations

import json
import logging
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from nav2_pyif.common.zenoh_config import ZenohOptions, connect_to, open_session
from nav2_pyif.server.host import ReachWatch

from tests.conftest import FIXTURES, free_port, wait_until
from tests.test_signals import TRACKER, WORKER, Command, host_command

pytestmark = pytest.mark.integration

SLOW_TO_LOAD = """
import time

from nav2_pyif import Controller

time.sleep(4)  # a model that takes a while to load


class Slow(Controller):
    def compute_velocity_commands(self, pose, velocity, goal_checker):
        raise NotImplementedError
"""


def test_nothing_says_serving_after_a_signal_stopped_the_host(tmp_path: Path) -> None:
    (tmp_path / "slow_load.py").write_text(SLOW_TO_LOAD)
    host = Command(
        tmp_path,
        *host_command(f"tcp/127.0.0.1:{free_port()}", "EchoController", "--path", str(tmp_path)),
        "--serve",
        "nav2_pyif/sig/Slow=slow_load:Slow",
    )
    host.wait_for(children={WORKER: 2, TRACKER: 1})  # loading: the handlers are in place
    code = host.signal_and_wait(signal.SIGINT)
    host.assert_ended_cleanly(code, signal.SIGINT)
    after = host.text().split("received SIGINT, shutting down", 1)[1]
    assert "serving" not in after, host.text()


def test_a_sighup_says_now_serving_once_per_key(tmp_path: Path) -> None:
    host = Command(tmp_path, *host_command(f"tcp/127.0.0.1:{free_port()}"))
    host.wait_for(children={WORKER: 1}, words="ready")
    assert re.search(r"serving echo_planners:EchoController on \S+ \(controller, worker \d+\)",
                     host.text()), host.text()  # fmt: skip
    host.proc.send_signal(signal.SIGHUP)
    host.wait_for(children={WORKER: 1}, words="now serving echo_planners:EchoController")
    time.sleep(1.0)  # a second line would follow at once
    host.assert_ended_cleanly(host.signal_and_wait(signal.SIGTERM), signal.SIGTERM)
    assert host.text().count("now serving") == 1, host.text()


def checked(watch: ReachWatch) -> bool:
    """Whether ``watch`` reaches something, after a check."""
    watch.check()
    return watch.reached


def test_a_listening_host_does_not_say_nothing_reached_yet_after_plugins_left(
    caplog: pytest.LogCaptureFixture,
) -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    host = open_session(ZenohOptions(listen=[endpoint], use_environment=False))
    watch = ReachWatch(host, [], [endpoint], grace=0.0, every=0.2)
    try:
        with caplog.at_level(logging.INFO, logger="nav2_pyif.server.host"):
            watch.check()
            assert "Zenoh: nothing reached yet" in caplog.text  # nobody came yet: true
            plugin = connect_to([endpoint], "client")
            assert wait_until(lambda: checked(watch), 10), caplog.text
            plugin.close()
            assert wait_until(lambda: not checked(watch), 10), caplog.text
            caplog.clear()
            deadline = time.monotonic() + 1.0  # five warning periods
            while time.monotonic() < deadline:
                watch.check()
                time.sleep(0.05)
    finally:
        host.close()
    assert "nothing reached yet" not in caplog.text, caplog.text
    assert caplog.text.count("Zenoh:") <= 1, caplog.text  # said once that it closed


def sim(tmp_path: Path, *args: str) -> tuple[subprocess.CompletedProcess[str], dict[str, Any]]:
    done = subprocess.run(
        [
            *(sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--no-progress"),
            *("--out", str(tmp_path), "--name", "run", *args),
        ],
        capture_output=True,
        text=True,
        timeout=100,
        env={**os.environ, "PYTHONPATH": str(FIXTURES)},
    )
    record = json.loads((tmp_path / "run.json").read_text())  # valid JSON: no Infinity
    return done, record


def test_sim_counts_the_controller_errors_against_the_cycles_driven(tmp_path: Path) -> None:
    done, _ = sim(
        tmp_path, "--controller", "echo_planners:FaultyController", "--param", "fault=zero_division"
    )
    assert done.returncode == 1, done.stderr
    cycles = int(re.search(r" in (\d+) cycles at ", done.stdout).group(1))  # type: ignore[union-attr]
    errors = re.search(r"controller errors (\d+) \((\d+) in the (\d+) cycles driven, 1 that ended "
                       r"the run\)", done.stdout)  # fmt: skip
    assert errors is not None, done.stdout
    total, driven, said = map(int, errors.groups())
    assert said == cycles and driven <= cycles and total == driven + 1, done.stdout


def test_sim_says_what_it_measured_of_the_clearance(tmp_path: Path) -> None:
    """A run that never drove measured no clearance: not "inf m", and JSON null."""
    done, record = sim(
        tmp_path, "--planner", "echo_planners:LinePlanner", "--planner-param", "mode=occupied"
    )
    assert done.returncode == 1, done.stderr
    assert "inf" not in done.stdout, done.stdout
    assert "minimum clearance not measured (no step driven)" in done.stdout, done.stdout
    assert record["summary"]["min_clearance_m"] is None
