"""``nav2-pyif record``: a live host streams its calls to a recorder over loopback Zenoh, which
writes them to MCAP as planner-host --record does; the replay cannot tell the two apart."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.server.recording.format import Recording, read_recording

from tests.test_record_replay import CONTROLLER, FOLLOW, GRID, PLANNER, nav2_pyif, replay

pytest.importorskip("mcap", reason="mcap is not installed (the record extra)")

SERVE = ("--serve", f"{FOLLOW}={CONTROLLER}", "--serve", f"{GRID}={PLANNER}")


def start_recorder(host: PlannerHostProcess, out: Path, *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [
            *(sys.executable, "-m", "nav2_pyif.tools.main", "record"),
            *("--connect", host.endpoint, "--key", FOLLOW, "--key", GRID, "-o", str(out), *args),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def wait_for_log(host: PlannerHostProcess, text: str, count: int, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while host.log().count(text) < count:
        assert time.monotonic() < deadline, f"not {count} x {text!r} in:\n{host.log()}"
        time.sleep(0.1)


def calls_of(recording: Recording, key: str) -> list[tuple[str, bytes, bytes | None, int, int]]:
    return [
        (c.op, c.request, c.reply, c.received_ns, c.answered_ns)
        for c in recording.calls
        if c.key == key
    ]


@pytest.fixture
def live_host(tmp_path: Path) -> Iterator[PlannerHostProcess]:
    host = PlannerHostProcess(
        args=[*SERVE, "--allow-live-record", "--record", str(tmp_path / "host.mcap")],
        log_level="INFO",
        log_path=tmp_path / "host.log",
    )
    with host:
        yield host


def test_a_live_recording_of_a_sim_run_replays_identically(
    live_host: PlannerHostProcess, tmp_path: Path
) -> None:
    path = tmp_path / "live.mcap"
    recorder = start_recorder(live_host, path)
    try:
        wait_for_log(live_host, "streaming its calls to a live recorder", 2)
        sim = nav2_pyif(
            *("sim", "--no-progress", "--connect", live_host.endpoint, "--wait", "60"),
            *("--timeout", "3", "--out", str(tmp_path)),
        )
        assert sim.returncode in (0, 1), sim.stdout + sim.stderr  # 3 sim s: not there yet
        time.sleep(0.5)  # the host publishes a batch at a time
        recorder.send_signal(signal.SIGINT)
        _out, err = recorder.communicate(timeout=30)
    finally:
        recorder.kill()
    assert recorder.returncode == 128 + signal.SIGINT, err
    wait_for_log(live_host, "stopped by its recorder", 2)
    recorded = read_recording([path])  # a complete file: its index was written
    assert not recorded.cut_short
    assert set(recorded.keys) == {FOLLOW, GRID}
    assert recorded.keys[GRID].planner["planner"] == PLANNER
    assert recorded.keys[FOLLOW].plugin_type == "controller"
    ops = [c.op for c in recorded.calls]
    assert ops.count("compute_velocity_commands") > 10
    assert {"configure", "activate", "create_plan", "set_plan", "cleanup"} <= set(ops)
    for call in recorded.calls:
        assert call.reply is not None and call.answered_ns >= call.received_ns > 0
    # the very calls the host recorded itself (--record), key by key: bytes and times
    assert live_host.stop() == 128 + signal.SIGTERM, live_host.log()
    by_host = read_recording([tmp_path / "host.mcap"])
    for key in (FOLLOW, GRID):
        assert calls_of(recorded, key) == calls_of(by_host, key)
    record = replay(path, tmp_path / "replay")
    summary = record["summary"]
    assert summary["calls"] == summary["identical"] > 10 and summary["errors"] == 0


def test_a_killed_recorder_stops_the_host_streaming(
    live_host: PlannerHostProcess, tmp_path: Path
) -> None:
    recorder = start_recorder(live_host, tmp_path / "killed.mcap")
    try:
        wait_for_log(live_host, "streaming its calls to a live recorder", 2)
        time.sleep(2.0)  # renewed at least once: a lease kept alive while the tool runs
        assert "lease ran out" not in live_host.log()
        recorder.send_signal(signal.SIGKILL)
        recorder.wait(timeout=10)
    finally:
        recorder.kill()
    killed = time.monotonic()
    wait_for_log(live_host, "its lease ran out", 2, timeout=10.0)
    assert time.monotonic() - killed < 3.0 + 1.5  # the lease, and the check's period


def test_a_host_that_does_not_allow_it_refuses(tmp_path: Path) -> None:
    with PlannerHostProcess(args=list(SERVE), log_path=tmp_path / "host.log") as host:
        recorder = start_recorder(host, tmp_path / "refused.mcap", "--duration", "5")
        _out, err = recorder.communicate(timeout=60)
    assert recorder.returncode == 1, err
    assert "live recording is off on this host" in err and "--allow-live-record" in err
    assert not (tmp_path / "refused.mcap").exists()


def test_record_options_fail_clearly(tmp_path: Path) -> None:
    missing = nav2_pyif("record", "--key", FOLLOW, "-o", str(tmp_path / "no" / "x.mcap"))
    assert missing.returncode == 2 and "--output" in missing.stderr
    bad = nav2_pyif("record", "--key", "/bad/", "-o", str(tmp_path / "x.mcap"))
    assert bad.returncode == 2 and "--key /bad/" in bad.stderr
    duration = nav2_pyif("record", "--key", FOLLOW, "-o", "x.mcap", "--duration", "0")
    assert duration.returncode == 2 and "--duration" in duration.stderr
    help_text = nav2_pyif("record", "--help").stdout
    assert "--allow-live-record" in help_text and "nav2-pyif replay" in help_text


def test_sigterm_and_duration_end_the_recorder_with_a_complete_file(
    live_host: PlannerHostProcess, tmp_path: Path
) -> None:
    terminated = start_recorder(live_host, tmp_path / "terminated.mcap")
    timed = start_recorder(live_host, tmp_path / "timed.mcap", "--duration", "2")
    try:
        wait_for_log(live_host, "streaming its calls to a live recorder", 4)
        terminated.send_signal(signal.SIGTERM)
        _out, err = terminated.communicate(timeout=30)
        assert terminated.returncode == 128 + signal.SIGTERM, err
        _out, err = timed.communicate(timeout=30)
        assert timed.returncode == 0, err
    finally:
        terminated.kill()
        timed.kill()
    for name in ("terminated.mcap", "timed.mcap"):
        assert not read_recording([tmp_path / name]).cut_short  # the index was written
    wait_for_log(live_host, "stopped by its recorder", 4)
