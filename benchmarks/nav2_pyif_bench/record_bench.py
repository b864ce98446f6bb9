"""What recording costs per control cycle, side by side in one run: three hosts serving the
same controller, one recording to MCAP itself (``--record``: "on"), one streaming each call to
a ``nav2-pyif record`` process beside it (``--allow-live-record``: "live") and one not
("off"), called in turn (round-robin, so load on the machine hits all alike) by the client
the runner uses.

Two cycles, each against both hosts: the bare cycle (compute_velocity_commands with a
constant command: the host's own cost is all there is, the worst case for the ratio) and the
cycle of a local costmap of 100 x 100 cells updated every fourth cycle (5 Hz at 20 Hz
control), which the recording writes each time. The cycles come at ``--rate`` (default
50 Hz; Nav2's controller_frequency is 20 Hz by default), as a controller_server sends them: the
recorder writes between cycles, after each reply. Target: the recording adds under 5 % to
the median cycle. Also printed: the recorder's own CPU time per call, from the host's log.
"""

from __future__ import annotations

import argparse
import contextlib
import re
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from geometry_msgs.msg import Twist
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.host_process import PlannerHostProcess, wait_alive
from nav2_pyif.common.option_types import non_negative_float, positive_int
from nav2_pyif.plan import Plan

from nav2_pyif_bench.checkers_bench import moving_robot
from nav2_pyif_bench.protocol_bench import costmap, open_session, progress
from nav2_pyif_bench.stats import Summary, header_row, verdict

# a key per host: each its own
KEYS = ("bench/off/FollowPath", "bench/on/FollowPath", "bench/live/FollowPath")
STATES = ("off", "on", "live")
PLANNER = "nav2_pyif_bench.planners:TrivialController"
TIMEOUTS = Timeouts(call=2.0, lifecycle=5.0, configure=30.0)
WARM_UP = 100
COSTMAP_EVERY = 4
TARGET = 1.05  # on / off, median


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--calls", type=positive_int, default=3000, help="cycles per variant, >= 1 (default 3000)"
    )
    p.add_argument(
        "--rate",
        type=non_negative_float,
        default=50.0,
        help="cycles per second, >= 0; 0: back to back, the recorder's worst case (default 50)",
    )
    p.add_argument("--quick", action="store_true", help="500 cycles per variant")


def run(args: argparse.Namespace) -> dict[str, Any]:
    calls = 500 if args.quick else args.calls
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_record_bench_") as tmp:
        path = Path(tmp) / "bench.mcap"
        off_entry, on_entry, live_entry = ([{"key": key, "planner": PLANNER}] for key in KEYS)
        live_args = ["--allow-live-record"]
        with (
            PlannerHostProcess(off_entry) as off,
            PlannerHostProcess(on_entry, args=["--record", str(path)], log_level="INFO") as on,
            PlannerHostProcess(live_entry, args=live_args, log_level="INFO") as live,
            _live_recorder(live, KEYS[2], Path(tmp) / "live.mcap") as recorder,
        ):
            session = open_session([off.endpoint, on.endpoint, live.endpoint])
            try:
                samples = _measure(session, [off, on, live], calls, args.rate)
            finally:
                session.close()
            on.stop()  # the recording's index is written as the host ends
            cpu = re.search(r"writing took ([0-9.]+) µs of CPU per call", on.log())
            on_calls = re.search(r"recording: ([0-9]+) call\(s\) in", on.log())
            recorder.send_signal(signal.SIGINT)
            _out, said = recorder.communicate(timeout=60)
        live_calls = re.search(r"record: ([0-9]+) call\(s\)", said)
        size = sum(p.stat().st_size for p in Path(tmp).glob("bench*.mcap"))
    return {
        "calls": calls,
        "rate": args.rate,
        "recorded_bytes": size,
        "recorded_calls": int(on_calls.group(1)) if on_calls else None,
        "live_recorded_calls": int(live_calls.group(1)) if live_calls else None,
        "recorder_cpu_us_per_call": float(cpu.group(1)) if cpu else None,
        "rows": {row: vars(Summary.of_ns(s)) for row, s in samples.items()},
    }


@contextlib.contextmanager
def _live_recorder(host: PlannerHostProcess, key: str, path: Path) -> Iterator[Any]:
    """``nav2-pyif record`` of ``key``, once the host streams to it."""
    command = [sys.executable, "-m", "nav2_pyif.tools.main", "record"]
    command += ["--connect", host.endpoint, "--key", key, "-o", str(path)]
    recorder = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while "streaming its calls to a live recorder" not in host.log():
            if recorder.poll() is not None or time.monotonic() > deadline:
                recorder.kill()
                said = recorder.communicate()[1]
                raise RuntimeError(f"nav2-pyif record did not start: {said}")
            time.sleep(0.1)
        yield recorder
    finally:
        recorder.kill()
        recorder.wait()


def _measure(
    session: Any, hosts: list[PlannerHostProcess], calls: int, rate: float
) -> dict[str, list[int]]:
    clients = [ControllerClient(session, key, costmap(100), timeouts=TIMEOUTS) for key in KEYS]
    for client, host in zip(clients, hosts, strict=True):
        # a host not found in time is reported with its exit code or its own log
        wait_alive(host, client.wait_for_host, timeout=30)
        client.configure()
        client.activate()
        client.set_plan(Plan([[0.0, 0.0], [50.0, 0.0]], "odom"))
    still = Twist()
    rows: dict[str, list[int]] = {
        f"{what}, record {state}": []
        for what in ("bare cycle", f"costmap every {COSTMAP_EVERY}th")
        for state in STATES
    }
    names = list(rows)
    progress(f"{calls} cycles of each variant {_rate(rate)}, interleaved: off, on, live")
    period_ns, next_ns = int(1e9 / rate) if rate else 0, time.perf_counter_ns()
    for i in range(calls + WARM_UP):
        if period_ns:
            next_ns += period_ns
            time.sleep(max(0, next_ns - time.perf_counter_ns()) / 1e9)
        robot = moving_robot(i)
        for variant in (0, 1):
            # a state first in one cycle, another in the next: the first call after the
            # sleep pays the wake-up, which would otherwise fall on one side only
            for turn in range(len(STATES)):
                state = (turn + i) % len(STATES)  # 0: off, 1: on, 2: live
                client = clients[state]
                if variant == 1 and i % COSTMAP_EVERY == 0:
                    client.update_costmap(costmap(100, version=i + 2))
                start = time.perf_counter_ns()
                client.compute_velocity_commands(robot, still)
                if i >= WARM_UP:
                    rows[names[len(STATES) * variant + state]].append(
                        time.perf_counter_ns() - start
                    )
    return rows


def _rate(rate: float) -> str:
    return f"at {rate:g} Hz" if rate else "back to back"


def report(results: dict[str, Any]) -> str:
    rows = {row: Summary(**v) for row, v in results["rows"].items()}
    lines = [
        f"the control cycle {_rate(results['rate'])} with recording off, on (planner-host "
        "--record) and live (nav2-pyif record beside the host), one run",
        header_row(36),
    ]
    lines += [summary.row(row, 36) for row, summary in rows.items()]
    names = list(rows)
    step = len(STATES)
    for first in range(0, len(names), step):
        off = names[first]
        for state, on in zip(STATES[1:], names[first + 1 : first + step], strict=True):
            median = rows[on].median_us / rows[off].median_us
            p99 = rows[on].p99_us / rows[off].p99_us
            lines.append(
                f"  {on.split(',')[0]}: {state} / off {median:.3f}x median, {p99:.3f}x p99 "
                f"(target median <= {TARGET:.2f}x): {verdict(median, '<=', TARGET, 3)}"
            )
    cpu = results["recorder_cpu_us_per_call"]
    lines.append(
        f"  recorded: {results['recorded_bytes'] / 2**20:.2f} MB for "
        f"{results['recorded_calls']} calls; the recorder's CPU per call: "
        + (f"{cpu:.1f} µs" if cpu is not None else "not in the host's log")
    )
    lines.append(
        f"  calls recorded: {results['recorded_calls']} by planner-host --record, "
        f"{results['live_recorded_calls']} by nav2-pyif record (the same calls, streamed)"
    )
    return "\n".join(lines)
