"""planner-host --record and nav2-pyif replay: a short run of the offline runner against a
real host over Zenoh on loopback is recorded, then replayed against the same planners (every
output identical, and identical between two replays) and against a changed controller (the
differences reported); a recording rotated at a small size replays from its last file alone."""

from __future__ import annotations

import json
import re
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from geometry_msgs.msg import Twist
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.server.recording.format import read_recording
from nav2_pyif.server.recording.recorder import Recorder, RecordOptions, key_metadata

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]
#: what bridge_plugin/test/nav2/test_record_replay.py recorded in a real Nav2: the one kept in
#: the repository (Jazzy, zenoh-pico), and each variant's latest where tests/test_nav2_launch.py
#: ran it here
KEPT_RECORDING = ROOT / "tests" / "fixtures" / "nav2_launch_run.mcap"
NAV2_RECORDINGS = [
    *([KEPT_RECORDING] if KEPT_RECORDING.is_file() else []),
    *sorted((ROOT / "build").glob("nav2_ws_*/nav2_run.mcap")),
]
pytest.importorskip("mcap", reason="mcap is not installed (the record extra)")

CONTROLLER = "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"
PLANNER = "nav2_pyif_planners.astar:AStar"
FOLLOW, GRID = "nav2_pyif/sim/FollowPath", "nav2_pyif/sim/GridBased"

#: the same controller at "a new version": half the speed, so every command differs
CHANGED = f"""
from {CONTROLLER.split(":")[0]} import RegulatedPurePursuit


class Slower(RegulatedPurePursuit):
    def compute_velocity_commands(self, pose, velocity, goal_checker):
        command = super().compute_velocity_commands(pose, velocity, goal_checker)
        command.twist.linear.x *= 0.5
        return command
"""


def nav2_pyif(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", *args],
        capture_output=True,
        text=True,
        timeout=180,
        cwd=cwd,
    )


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A short sim run recorded by a real host, which a SIGTERM then stops."""
    out = tmp_path_factory.mktemp("recorded")
    path = out / "run.mcap"
    host = PlannerHostProcess(
        args=[
            *("--serve", f"{FOLLOW}={CONTROLLER}", "--serve", f"{GRID}={PLANNER}"),
            *("--record", str(path)),
        ],
        log_level="INFO",
        log_path=out / "host.log",
    )
    with host:
        sim = nav2_pyif(
            *("sim", "--no-progress", "--connect", host.endpoint, "--wait", "60"),
            *("--timeout", "3", "--out", str(out)),
        )
        assert sim.returncode in (0, 1), sim.stdout + sim.stderr  # 3 sim s: not there yet
        assert host.stop() == 128 + signal.SIGTERM, host.log()
    assert "recording: " in host.log() and path.is_file(), host.log()
    yield path


def replay(recording: Path | list[Path], out: Path, *args: str) -> dict[str, Any]:
    out.mkdir(exist_ok=True)
    files = [str(p) for p in (recording if isinstance(recording, list) else [recording])]
    result = nav2_pyif("replay", *files, "--out", str(out), "--name", "run_replay", *args, cwd=out)
    assert result.returncode == 0, result.stdout + result.stderr
    assert (out / "run_replay.png").stat().st_size > 0
    record: dict[str, Any] = json.loads((out / "run_replay.json").read_text())
    return record


def test_a_recording_holds_every_call_of_the_run(recording: Path) -> None:
    recorded = read_recording([recording])
    assert set(recorded.keys) == {FOLLOW, GRID}
    assert recorded.keys[FOLLOW].plugin_type == "controller"
    assert recorded.keys[GRID].planner["planner"] == PLANNER
    ops = [c.op for c in recorded.calls]
    assert ops.count("compute_velocity_commands") > 10
    assert {"configure", "activate", "create_plan", "set_plan", "cleanup"} <= set(ops)
    for call in recorded.calls:
        assert call.reply is not None and call.answered_ns >= call.received_ns > 0
    # the costmap went with the calls that changed it, and only with those
    cycles = [c.request for c in recorded.calls if c.op == "compute_velocity_commands"]
    assert 0 < sum(b"costmap" in r for r in cycles) < len(cycles)


def test_replaying_the_same_planners_is_identical_and_deterministic(
    recording: Path, tmp_path: Path
) -> None:
    first = replay(recording, tmp_path / "a")
    second = replay(recording, tmp_path / "b", "--isolation", "none")
    summary = first["summary"]
    assert summary["calls"] == summary["identical"] > 10 and summary["errors"] == 0
    cycles = summary["by_key"][FOLLOW]["compute_velocity_commands"]
    assert cycles["max_abs_dv"] == cycles["max_abs_dw"] == 0.0
    assert summary["by_key"][GRID]["create_plan"]["plan_max"] == 0.0
    assert [c["output"] for c in first["calls"]] == [c["output"] for c in second["calls"]]


def test_a_changed_controller_is_replayed_with_its_differences(
    recording: Path, tmp_path: Path
) -> None:
    (tmp_path / "slower.py").write_text(CHANGED)
    record = replay(recording, tmp_path, "--planner", "slower:Slower", "--isolation", "none")
    summary = record["summary"]
    assert set(summary["by_key"]) == {FOLLOW}  # --planner: the keys of its plugin type
    assert summary["planners"][FOLLOW] == "slower:Slower"
    cycles = summary["by_key"][FOLLOW]["compute_velocity_commands"]
    assert cycles["errors"] == 0 and cycles["identical"] < cycles["calls"]
    assert cycles["max_abs_dv"] > 0.01
    moving = [c for c in record["calls"] if c["op"] == "compute_velocity_commands"]
    assert all(c["dv"] <= 0 and c["compute_ms"] >= 0 for c in moving)


def test_a_recording_of_a_real_nav2_run_replays(tmp_path: Path) -> None:
    # the kept one always; tests/test_nav2_launch.py adds a new one per variant it ran here
    assert KEPT_RECORDING in NAV2_RECORDINGS, f"{KEPT_RECORDING} is missing"
    (tmp_path / "slower.py").write_text(CHANGED)
    for n, recording in enumerate(NAV2_RECORDINGS):
        same = replay(recording, tmp_path / f"{n}_{recording.parent.name}", "--isolation", "none")
        assert same["summary"]["calls"] == same["summary"]["identical"] > 10, recording
        changed = replay(recording, tmp_path, "--planner", "slower:Slower", "--isolation", "none")
        (controller,) = changed["summary"]["by_key"].values()
        assert controller["compute_velocity_commands"]["max_abs_dv"] > 0.01, recording


def test_a_rotated_recording_replays_from_its_last_file_alone(
    recording: Path, tmp_path: Path
) -> None:
    """Each rotated file starts with what restores the live sessions (configure with the
    latest costmap, activate, the plan): its calls replay as they were answered."""
    calls = read_recording([recording]).calls
    first = tmp_path / "rotated.mcap"
    metadata = {FOLLOW: key_metadata("controller", None)}
    metadata[FOLLOW]["planner"] = json.dumps({"planner": CONTROLLER})
    recorder = Recorder(RecordOptions(first, max_bytes=8000, max_files=3), metadata)
    for call in calls:
        if call.key == FOLLOW:
            assert call.reply is not None
            recorder.add(FOLLOW, call.op, call.request, call.reply, call.received_ns, 0)
    recorder.close()
    kept = recorder.paths
    assert len(kept) == 3 and kept[-1] != first and not first.exists()  # the oldest went
    assert all(p.stat().st_size < 8000 + 64_000 for p in kept)
    last = read_recording([kept[-1]])
    assert [c.op for c in last.calls if c.restore][:2] == ["configure", "activate"]
    record = replay(kept[-1], tmp_path, "--isolation", "none")
    assert record["summary"]["restored"] >= 3  # configure, activate, set_plan
    assert record["summary"]["calls"] == record["summary"]["identical"] > 0
    # a host that did not end cleanly leaves a file without its index: its complete chunks
    # still read, and the replay says where it stopped
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(kept[0].read_bytes()[: kept[0].stat().st_size * 3 // 4])
    whole, partial = read_recording([kept[0]]), read_recording([cut])
    assert partial.cut_short == [cut] and not whole.cut_short
    assert 0 < len(partial.calls) < len(whole.calls)
    result = nav2_pyif("replay", str(cut), "--out", str(tmp_path), "--isolation", "none")
    assert result.returncode == 0 and "ends before its index" in result.stderr, result.stderr
    # all three files together: the same calls, restored only where no earlier file was
    together = read_recording(kept[::-1])
    assert [c.sequence for c in together.calls if not c.restore] == sorted(
        c.sequence for c in together.calls if not c.restore
    )
    assert sum(c.restore for c in together.calls) == sum(
        c.restore for c in read_recording([kept[0]]).calls
    )


def test_record_and_replay_options_fail_clearly(recording: Path, tmp_path: Path) -> None:
    host = subprocess.run(
        [
            sys.executable,
            "-m",
            "nav2_pyif.server.cli",
            "--serve",
            f"{FOLLOW}={CONTROLLER}",
            "--record-key",
            FOLLOW,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert host.returncode == 2 and "--record-key needs --record" in host.stderr
    missing = nav2_pyif("replay", str(tmp_path / "none.mcap"))
    assert missing.returncode == 2 and "none.mcap: no such file" in missing.stderr
    other = nav2_pyif("replay", str(recording), "--serve", "nav2_pyif/x/FollowPath=m:C")
    assert other.returncode == 2 and "--serve nav2_pyif/x/FollowPath: not recorded" in other.stderr
    help_text = nav2_pyif("replay", "--help").stdout
    assert "--planner" in help_text and "planner-host" in help_text


def test_the_record_benchmark_prints_off_and_on_side_by_side() -> None:
    """Figures are not asserted (BENCHMARKS.md quotes a full run); the table is."""
    result = subprocess.run(
        [sys.executable, "-m", "nav2_pyif_bench.cli", "record", "--calls", "100", "--rate", "200"],
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    for row in ("bare cycle, record off", "bare cycle, record on", "costmap every 4th, record on"):
        assert row in result.stdout
    assert "bare cycle, record live" in result.stdout  # nav2-pyif record beside a host
    assert re.search(r"bare cycle: on / off [0-9.]+x median, [0-9.]+x p99", result.stdout)
    assert re.search(r"bare cycle: live / off [0-9.]+x median, [0-9.]+x p99", result.stdout)
    # every call the host answered reached the live recorder too
    counted = re.search(
        r"calls recorded: ([0-9]+) by planner-host --record, ([0-9]+) by", result.stdout
    )
    assert counted and counted.group(1) == counted.group(2), result.stdout
    assert re.search(r"the recorder's CPU per call: [0-9.]+ µs", result.stdout), result.stdout


#: a controller slow enough for a signal to find the replay mid-way
SLEEPY = f"""
import time

from {CONTROLLER.split(":")[0]} import RegulatedPurePursuit


class Sleepy(RegulatedPurePursuit):
    def compute_velocity_commands(self, pose, velocity, goal_checker):
        time.sleep(0.2)
        return super().compute_velocity_commands(pose, velocity, goal_checker)
"""


def _children(pid: int) -> set[int]:
    found: set[int] = set()
    for task in Path(f"/proc/{pid}/task").iterdir():
        found |= {int(p) for p in (task / "children").read_text().split()}
    return found


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_ends_the_replay_and_its_workers(
    recording: Path, tmp_path: Path, signum: int
) -> None:
    (tmp_path / "sleepy.py").write_text(SLEEPY)
    replay = subprocess.Popen(
        [
            *(sys.executable, "-m", "nav2_pyif.tools.main", "replay", str(recording)),
            *("--planner", "sleepy:Sleepy", "--out", str(tmp_path)),
        ],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 60
        while not _children(replay.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        workers = _children(replay.pid)
        assert workers, "the replay started no worker"
        time.sleep(3.0)  # loaded, configured, replaying the slow cycles
        replay.send_signal(signum)
        _, err = replay.communicate(timeout=30)
    finally:
        if replay.poll() is None:
            replay.kill()
    assert replay.returncode == 128 + signum, err
    assert f"stopped by {signal.Signals(signum).name}" in err
    # a worker ends when its pipes to the replay close: at once, but not in the same instant
    deadline = time.monotonic() + 10
    while any(_running(w) for w in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not [w for w in workers if _running(w)], "a worker outlived the replay"


def _running(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except FileNotFoundError:
        return False
    return "State:\tZ" not in status


def test_batched_cycles_are_recorded_per_robot(tmp_path: Path) -> None:
    """planner-host --batch answers a fleet's cycles in one call of the planner: each robot's
    cycle is recorded on its own key. Replayed one by one, BatchEcho says it served a batch
    of one (angular z), which the replay reports as dw."""
    from tests.conftest import FIXTURES
    from tests.test_batched import ROBOTS, Fleet, key

    path = tmp_path / "fleet.mcap"
    fleet = Fleet(tmp_path, "batch_planners:BatchEcho", "--record", str(path))
    try:
        batched = fleet.batched_round()
        assert [r.twist.angular.z for r in batched] == [ROBOTS] * ROBOTS
        assert fleet.host.stop() == 128 + signal.SIGTERM, fleet.host.log()
    finally:
        fleet.close()
    recorded = read_recording([path])
    for i in range(ROBOTS):
        cycles = [
            c for c in recorded.calls if c.key == key(i) and c.op == "compute_velocity_commands"
        ]
        assert cycles and all(c.reply is not None for c in cycles), key(i)
    record = replay(path, tmp_path / "out", "--path", str(FIXTURES), "--isolation", "none")
    for i in range(ROBOTS):
        cycles = record["summary"]["by_key"][key(i)]["compute_velocity_commands"]
        assert cycles["errors"] == 0 and cycles["max_abs_dw"] == ROBOTS - 1, cycles


def test_a_hot_swap_is_in_the_recording_and_the_replay_says_so(
    start_host: Any, zsession_factory: Any, tmp_path: Path
) -> None:
    from tests.test_host_e2e import controller, pose

    path = tmp_path / "swap.mcap"
    host = start_host(
        *("--key", FOLLOW, "--planner", "echo_planners:EchoController", "--record", str(path)),
        *("--pid-file", str(tmp_path / "host.pid")),
    )
    client = controller(zsession_factory, host, key=FOLLOW)
    client.configure()
    client.activate()
    client.compute_velocity_commands(pose(), Twist())
    host.proc.send_signal(signal.SIGHUP)  # a fresh import of the same planner, sessions kept
    deadline = time.monotonic() + 60
    while "now serving" not in host.log() and time.monotonic() < deadline:
        time.sleep(0.2)
    client.compute_velocity_commands(pose(2.0, 2.0), Twist())
    assert host.stop() == 128 + signal.SIGTERM, host.log()
    (reload,) = read_recording([path]).reloads
    assert reload[1:] == (FOLLOW, "echo_planners:EchoController")
    from tests.conftest import FIXTURES

    record = replay(path, tmp_path / "out", "--path", str(FIXTURES), "--isolation", "none")
    assert [r["key"] for r in record["summary"]["reloads"]] == [FOLLOW]
    assert record["summary"]["calls"] == record["summary"]["identical"] >= 4


def test_a_host_started_again_on_its_file_goes_on_numbering(
    start_host: Any, zsession_factory: Any, tmp_path: Path
) -> None:
    """--respawn starts the host again with the same --record FILE: the first run's calls
    stay, and both runs replay in order."""
    from tests.conftest import FIXTURES
    from tests.test_host_e2e import controller, pose

    path = tmp_path / "runs.mcap"
    for x in (1.0, 2.0):
        host = start_host("--key", FOLLOW, "--planner", "echo_planners:EchoController",
                          "--record", str(path))  # fmt: skip
        client = controller(zsession_factory, host, key=FOLLOW)
        client.configure()
        client.activate()
        client.compute_velocity_commands(pose(x, x), Twist())
        assert host.stop() == 128 + signal.SIGTERM, host.log()
    files = [path, tmp_path / "runs.1.mcap"]
    assert set(tmp_path.glob("runs*.mcap")) == set(files)
    calls = read_recording(files[::-1]).calls
    assert [c.op for c in calls] == ["configure", "activate", "compute_velocity_commands"] * 2
    assert calls[0].received_ns < calls[3].received_ns
    record = replay(files, tmp_path / "out", "--path", str(FIXTURES))
    assert record["summary"]["calls"] == record["summary"]["identical"] == 6
