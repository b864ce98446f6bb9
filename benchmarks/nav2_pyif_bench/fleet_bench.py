"""Many robots, one planner host: N controller keys served by one host (one worker process
each, the default), N clients calling at 20 Hz from several client processes. Reports the
latency, the missed deadlines (no valid reply within the 50 ms period) and the CPU the host
and its workers used, to show where the 2-core limit is."""

from __future__ import annotations

import argparse
import multiprocessing
import os
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

PERIOD = 0.05
PLANNER = "nav2_pyif_bench.planners:TrivialController"


def key(i: int) -> str:
    return f"nav2_pyif/robot{i}/FollowPath"


def _robot(
    endpoint_session: Any,
    index: int,
    seconds: float,
    out: list[tuple[float, bool]],
    start_at: float,
) -> None:
    from geometry_msgs.msg import PoseStamped, Twist
    from nav2_pyif import Costmap, Plan
    from nav2_pyif.client import ControllerClient, Timeouts
    from nav2_pyif.exceptions import Nav2Error

    client = ControllerClient(
        endpoint_session,
        key(index),
        Costmap(np.zeros((60, 60), np.uint8), 0.05, version=1),
        timeouts=Timeouts(call=10.0, lifecycle=30, configure=60),
    )
    client.wait_for_host(180)
    client.configure()  # dozens of robots set up at once: generous timeouts
    client.activate()
    client.set_plan(Plan(np.zeros((100, 3)), "odom"))
    client.timeouts = Timeouts(call=PERIOD, lifecycle=30, configure=60)  # the control loop
    pose, velocity = PoseStamped(), Twist()
    time.sleep(max(0.0, start_at - time.monotonic()))
    next_tick = time.monotonic() + (index % 20) * PERIOD / 20  # spread robots over a period
    end = next_tick + seconds
    while next_tick < end:
        time.sleep(max(0.0, next_tick - time.monotonic()))
        started = time.perf_counter()
        try:
            client.compute_velocity_commands(pose, velocity)
            out.append((time.perf_counter() - started, True))
        except Nav2Error:
            out.append((time.perf_counter() - started, False))
        next_tick += PERIOD
    client.close()


def _client_process(
    endpoint: str, indices: list[int], seconds: float, start_at: float, queue: Any
) -> None:
    from nav2_pyif_bench.protocol_bench import open_session

    session = open_session([endpoint])
    results: list[tuple[float, bool]] = []
    threads = [
        threading.Thread(target=_robot, args=(session, i, seconds, results, start_at))
        for i in indices
    ]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    session.close()
    queue.put(results)


def _cpu_seconds(pid: int) -> float:
    """utime + stime of a process and its children (the workers), from /proc."""
    ticks = os.sysconf("SC_CLK_TCK")
    total = 0.0
    children = Path(f"/proc/{pid}/task/{pid}/children").read_text().split()
    for p in [pid, *map(int, children)]:
        fields = Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()
        total += (int(fields[11]) + int(fields[12])) / ticks
    return total


def run_one(robots: int, seconds: float, isolation: str) -> dict[str, Any]:
    from nav2_pyif.common.host_process import PlannerHostProcess

    entries = [{"key": key(i), "planner": PLANNER} for i in range(robots)]
    host = PlannerHostProcess(entries, args=["--isolation", isolation])
    with host:
        assert host.proc is not None
        ctx = multiprocessing.get_context("spawn")
        queue = ctx.Queue()
        processes = min(robots, 4)
        groups = [list(range(robots))[g::processes] for g in range(processes)]
        start_at = time.monotonic() + 15.0 + 1.0 * robots  # after every robot configured
        clients = [
            ctx.Process(target=_client_process, args=(host.endpoint, g, seconds, start_at, queue))
            for g in groups
        ]
        try:
            for c in clients:
                c.start()
            time.sleep(max(0.0, start_at - time.monotonic()))
            cpu_before, wall_before = _cpu_seconds(host.proc.pid), time.monotonic()
            samples: list[tuple[float, bool]] = []
            for _ in clients:
                samples += queue.get(timeout=seconds + 300)
            cpu = _cpu_seconds(host.proc.pid) - cpu_before
            wall = time.monotonic() - wall_before
            for c in clients:
                c.join(30)
        finally:  # also on a signal or an error: no client process is left behind
            for c in clients:
                if c.pid is not None and c.is_alive():
                    c.terminate()
                    c.join(5)
    latency = np.array([s[0] for s in samples if s[1]]) * 1000
    missed = sum(1 for s in samples if not s[1] or s[0] > PERIOD)
    return {
        "robots": robots,
        "calls": len(samples),
        "calls_per_s": len(samples) / seconds,
        "median_ms": float(np.median(latency)) if len(latency) else float("nan"),
        "p99_ms": float(np.percentile(latency, 99)) if len(latency) else float("nan"),
        "missed": missed,
        "missed_pct": 100.0 * missed / max(1, len(samples)),
        "host_cpu_cores": cpu / wall,
        "isolation": isolation,
    }


def run(args: argparse.Namespace) -> dict[str, Any]:
    results = {}
    for n in args.robots:
        print(f"  … {n} robot(s) at 20 Hz for {args.seconds:g} s ({args.isolation})", flush=True)
        results[str(n)] = run_one(n, args.seconds, args.isolation)
    return results


def report(results: dict[str, Any]) -> str:
    isolation = next(iter(results.values()))["isolation"] if results else "process"
    workers = "one worker each" if isolation == "process" else "no workers: --isolation none"
    lines = [
        f"fleet: N controllers on one host ({workers}), clients at 20 Hz",
        f"  {'robots':>6} {'calls/s':>8} {'median':>9} {'p99':>9} {'missed':>12} {'host CPU':>9}",
    ]
    for r in results.values():
        lines.append(
            f"  {r['robots']:>6} {r['calls_per_s']:>8.0f} {r['median_ms']:>6.2f} ms "
            f"{r['p99_ms']:>6.2f} ms {r['missed']:>5} ({r['missed_pct']:4.1f} %) "
            f"{r['host_cpu_cores']:>6.2f} cores"
        )
    lines.append("  missed: no valid reply within the 50 ms control period")
    return "\n".join(lines)
