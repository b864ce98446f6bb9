"""A hostile peer beside a well-formed client, over real Zenoh: a planner host serving the
reference pure pursuit controller; a fuzzing process (hostile_fuzzer) sending mutated
requests to every key and op of it at full rate; a ControllerClient at 20 Hz beside it.

Measured: the client's reply latency against its period (a reply later than the period is a
missed period), the host's and the worker's RSS over time (a line fit: KiB per minute), the
modules the host and worker imported while the peer ran (Python's -X importtime lines in
their log), and what the peer got back (each query: a typed reply, or dropped and counted by
the host: its admin info says how many).

    nav2-pyif-bench hostile --seconds 300
"""

from __future__ import annotations

import itertools
import json
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif import Costmap, Plan
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.host_process import PlannerHostProcess, wait_alive
from nav2_pyif.exceptions import Nav2Error
from nav2_pyif_protocol.bounded import unpack_bounded

from nav2_pyif_bench.protocol_bench import open_session

KEY = "nav2_pyif/hostile/FollowPath"
PLANNER = "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"
PERIOD = 0.05  # 20 Hz, as controller_server's default
#: the latency histogram's upper bounds [ms]
BUCKETS_MS = (2, 5, 10, 20, 50)
IMPORT_LINE = "import time:"
WARM_S = 20.0
STALL_S = 0.025


def _rss_kib(pid: int) -> int:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    except OSError:
        pass
    return 0


def _children(pid: int) -> list[int]:
    try:
        return [int(c) for c in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        return []


class MemoryWatch(threading.Thread):
    """RSS of the host and of its worker(s), every ``every`` seconds, until stopped."""

    def __init__(self, host_pid: int, every: float = 0.5) -> None:
        super().__init__(daemon=True)
        self.host_pid, self.every = host_pid, every
        self.samples: list[tuple[float, int, int]] = []  # (s, host KiB, workers KiB)
        self._done = threading.Event()

    def run(self) -> None:
        started = time.monotonic()
        while not self._done.wait(self.every):
            workers = sum(_rss_kib(c) for c in _children(self.host_pid))
            self.samples.append((time.monotonic() - started, _rss_kib(self.host_pid), workers))

    def stop(self) -> None:
        self._done.set()
        self.join()

    def slope_kib_per_min(self, column: int) -> float:
        """The line fit of a column over the run after its warm-up: the first fifth, and at
        least WARM_S (the host's RSS grows ~10 MiB in its first half minute under the peer,
        then stays: Zenoh's buffers and the allocator's arenas filling)."""
        end = self.samples[-1][0] if self.samples else 0.0
        warm = [s for s in self.samples if s[0] >= max(WARM_S, end / 5)]
        if len(warm) < 3:
            return 0.0
        x = np.array([s[0] for s in warm])
        y = np.array([s[column] for s in warm], float)
        return float(np.polyfit(x, y, 1)[0] * 60.0)


def _client(session: Any, host: PlannerHostProcess) -> ControllerClient:
    costmap = Costmap(np.zeros((100, 100), np.uint8), 0.05, version=1)
    client = ControllerClient(
        session, KEY, costmap, timeouts=Timeouts(call=2.0, lifecycle=10, configure=30)
    )
    wait_alive(host, client.wait_for_host)
    client.configure()
    client.activate()
    path = np.column_stack([np.linspace(0.0, 4.0, 80), np.full(80, 2.5)])
    client.set_plan(Plan(path, "map"))
    return client


def _pose() -> PoseStamped:
    pose = PoseStamped()
    pose.header.frame_id = "map"
    pose.pose.position.x, pose.pose.position.y = 0.2, 2.5
    pose.pose.orientation.w = 1.0
    return pose


def _host_info(session: Any) -> dict[str, Any]:
    for reply in session.get(f"{KEY}/admin/info", timeout=5.0):
        if reply.ok is not None:
            info = unpack_bounded(reply.ok.payload.to_bytes())
            if isinstance(info, dict):
                return info
    return {}


class StallProbe(threading.Thread):
    """When this process could not run for a while: a thread that sleeps 5 ms at a time
    notes each sleep that lasted over STALL_S. A client's late reply during such a stall was
    the machine's doing (this project's test machine runs two cores for many jobs), not
    necessarily the host's; the figures say how many missed periods fall in one."""

    def __init__(self) -> None:
        super().__init__(daemon=True)
        self.stalls: list[tuple[float, float]] = []  # (from, to), monotonic
        self._done = threading.Event()

    def run(self) -> None:
        while not self._done.is_set():
            before = time.monotonic()
            time.sleep(0.005)
            after = time.monotonic()
            if after - before > STALL_S:
                self.stalls.append((before, after))

    def stop(self) -> None:
        self._done.set()
        self.join()

    def during(self, start: float, end: float) -> bool:
        return any(a < end and b > start for a, b in self.stalls)


def _drive(client: ControllerClient, until: float) -> tuple[list[tuple[float, float]], list[str]]:
    """Control cycles at 20 Hz until ``until`` (monotonic): each one's (start, latency) [s],
    and the errors (a typed error reply is an answer in time all the same)."""
    pose, velocity = _pose(), Twist()
    latencies: list[tuple[float, float]] = []
    errors: list[str] = []
    next_cycle = time.monotonic()
    while next_cycle < until:
        started = time.monotonic()
        try:
            client.compute_velocity_commands(pose, velocity)
        except Nav2Error as exc:
            errors.append(f"{type(exc).__name__}: {exc}"[:200])
        latencies.append((started, time.monotonic() - started))
        next_cycle += PERIOD
        time.sleep(max(0.0, next_cycle - time.monotonic()))
    return latencies, errors


def _imports_since(log: Path, offset: int) -> list[str]:
    with open(log, "rb") as f:
        f.seek(offset)
        text = f.read().decode(errors="replace")
    return [
        line.rsplit("|", 1)[-1].strip()
        for line in text.splitlines()
        if IMPORT_LINE in line and "imported package" not in line
    ]


def _peer(host: PlannerHostProcess, *args: str, report: Path) -> subprocess.Popen[bytes]:
    return subprocess.Popen(
        [sys.executable, "-m", "nav2_pyif_bench.hostile_fuzzer", "--connect", host.endpoint,
         "--key", KEY, "--report", str(report), *args]
    )  # fmt: skip


def run(seconds: float, seed: int = 1) -> dict[str, Any]:
    """The client alone for a moment, then with the hostile peer for ``seconds``."""
    peers: list[subprocess.Popen[bytes]] = []  # stopped on every way out, a signal's too
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_hostile_") as tmp:
        log = Path(tmp) / "host.log"
        report = Path(tmp) / "peer.json"
        host = PlannerHostProcess(
            [{"key": KEY, "planner": PLANNER}],
            log_level="WARNING",
            log_path=log,
            env={"PYTHONPROFILEIMPORTTIME": "1"},  # host and worker log each import
        )
        with host:
            assert host.proc is not None
            session = open_session([host.endpoint])
            try:
                client = _client(session, host)
                _drive(client, time.monotonic() + 2.0)  # warm: first cycles, allocator pools
                peers.append(_peer(host, "--seeds-only", report=Path(tmp) / "seeds.json"))
                if peers[-1].wait(timeout=120) != 0:
                    raise RuntimeError(f"the peer's seeds pass failed:\n{host.log()[-3000:]}")
                before = _host_info(session)
                mark = log.stat().st_size
                memory = MemoryWatch(host.proc.pid)
                memory.start()
                peers.append(
                    _peer(host, "--seconds", str(seconds), "--seed", str(seed), report=report)
                )
                probe = StallProbe()
                probe.start()
                cycles, errors = _drive(client, time.monotonic() + seconds)
                probe.stop()
                peer_code = peers[-1].wait(timeout=60)
                memory.stop()
                after = _host_info(session)
                imported = _imports_since(log, mark)
                client.close()
            finally:
                for peer in peers:
                    if peer.poll() is None:
                        peer.kill()
                        peer.wait()
                session.close()
            host.check_alive()
        peer_report = json.loads(report.read_text()) if report.exists() else {}
    missed = [(t, d) for t, d in cycles if d > PERIOD]
    return _figures(seconds, [d for _, d in cycles], errors, memory, imported, before, after,
                    peer_report) | {
        "peer_exit_code": peer_code,
        "missed_in_machine_stalls": sum(1 for t, d in missed if probe.during(t, t + d)),
        "machine_stalls": len(probe.stalls),
        "longest_machine_stall_ms": 1000 * max((b - a for a, b in probe.stalls), default=0.0),
    }  # fmt: skip


def _figures(
    seconds: float,
    latencies: list[float],
    errors: list[str],
    memory: MemoryWatch,
    imported: list[str],
    before: dict[str, Any],
    after: dict[str, Any],
    peer: dict[str, Any],
) -> dict[str, Any]:
    ms = np.array(latencies) * 1000.0
    edges = [0, *BUCKETS_MS, float("inf")]
    histogram = {
        f"{lo:g}-{hi:g} ms": int(((ms >= lo) & (ms < hi)).sum())
        for lo, hi in itertools.pairwise(edges)
    }
    first, last = memory.samples[0], memory.samples[-1]
    return {
        "seconds": seconds,
        "cycles": len(latencies),
        "missed": int((ms > PERIOD * 1000).sum()),
        "latency_ms": {
            "median": float(np.median(ms)),
            "p99": float(np.percentile(ms, 99)),
            "max": float(ms.max()),
        },
        "latency_histogram": histogram,
        "client_errors": len(errors),
        "client_error_examples": errors[:5],
        "rss_kib": {
            "host_first": first[1],
            "host_last": last[1],
            "worker_first": first[2],
            "worker_last": last[2],
            "host_slope_per_min": memory.slope_kib_per_min(1),
            "worker_slope_per_min": memory.slope_kib_per_min(2),
            "samples": len(memory.samples),
            "series": [list(s) for s in memory.samples[:: max(1, len(memory.samples) // 40)]],
        },
        "imported": imported,
        "host_dropped": after.get("dropped", 0) - before.get("dropped", 0),
        "host_refused_ops": after.get("refused_ops", 0) - before.get("refused_ops", 0),
        "sessions": [before.get("sessions", 0), after.get("sessions", 0)],
        "peer": peer,
    }


def report(r: dict[str, Any]) -> str:
    peer = r["peer"]
    outcomes = peer.get("outcomes", {})
    lat, rss = r["latency_ms"], r["rss_kib"]
    lines = [
        f"hostile peer: {peer.get('sent', 0)} mutated queries in {r['seconds']:g} s "
        f"({peer.get('rate_hz', 0):.0f}/s) to every key and op of a live host, beside a "
        "20 Hz client",
        "",
        "| the peer's queries | count |",
        "|---|---:|",
        *(f"| {name} | {count} |" for name, count in sorted(outcomes.items())),
        f"| dropped, as the host counted them | {r['host_dropped']} |",
        "",
        "| the 20 Hz client | value |",
        "|---|---:|",
        f"| cycles | {r['cycles']} |",
        f"| missed periods (reply later than 50 ms) | {r['missed']} |",
        f"| of which while this machine stalled every process (> 25 ms) | "
        f"{r['missed_in_machine_stalls']} |",
        f"| machine stalls, longest [ms] | {r['machine_stalls']}, "
        f"{r['longest_machine_stall_ms']:.0f} |",
        f"| latency median / p99 / max [ms] | {lat['median']:.2f} / {lat['p99']:.2f} / "
        f"{lat['max']:.2f} |",
        *(f"| latency {bucket} | {n} |" for bucket, n in r["latency_histogram"].items()),
        f"| error replies | {r['client_errors']} |",
        "",
        "| memory (RSS) | first [MiB] | last [MiB] | fitted slope [KiB/min] |",
        "|---|---:|---:|---:|",
        f"| host | {rss['host_first'] / 1024:.1f} | {rss['host_last'] / 1024:.1f} | "
        f"{rss['host_slope_per_min']:.0f} |",
        f"| worker | {rss['worker_first'] / 1024:.1f} | {rss['worker_last'] / 1024:.1f} | "
        f"{rss['worker_slope_per_min']:.0f} |",
        "",
        f"modules imported while the peer ran: {len(r['imported'])} "
        f"{r['imported'][:10] if r['imported'] else ''}",
        f"contract broken: {outcomes.get('contract broken', 0)} {peer.get('broken', [])[:5]}",
        "the peer's slowest queries: " + "; ".join(peer.get("slowest", [])),
    ]
    return "\n".join(lines)
