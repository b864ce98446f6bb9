"""Reliability figures for RELIABILITY.md: hot swap under a 20 Hz control loop, memory over a
long run of calls, and repeated lifecycle cycles."""

from __future__ import annotations

import argparse
import itertools
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
from nav2_pyif.tools.admin import request_reload

from nav2_pyif_bench.protocol_bench import open_session

KEY = "nav2_pyif/bench/FollowPath"
V1 = "nav2_pyif_bench.planners:TrivialController"
V2 = "nav2_pyif_bench.planners:TrivialControllerV2"
SWAPPABLE = ["--allow-remote-reload", "--reload-allow", "nav2_pyif_bench.planners:*"]


def _client(session: Any, host: PlannerHostProcess) -> ControllerClient:
    costmap = Costmap(np.zeros((100, 100), np.uint8), 0.05, version=1)
    client = ControllerClient(
        session, KEY, costmap, timeouts=Timeouts(call=0.05, lifecycle=10, configure=30)
    )
    wait_alive(host, client.wait_for_host)
    return client


def hot_swap(swaps: int, period: float = 0.05) -> dict[str, Any]:
    """Swap V1 <-> V2 ``swaps`` times, 2 s apart, while calling at 1/period Hz."""
    with PlannerHostProcess([{"key": KEY, "planner": V1}], args=SWAPPABLE) as host:
        session = open_session([host.endpoint])
        client = _client(session, host)
        client.configure()
        client.activate()
        client.set_plan(Plan(np.zeros((500, 3)), "odom"))
        swap_times: list[float] = []
        swap_windows: list[tuple[float, float]] = []
        failures: list[str] = []

        def swapper() -> None:
            for i in range(swaps):
                time.sleep(2.0)
                started = time.monotonic()
                request_reload(session, KEY, planner=V2 if i % 2 == 0 else V1)
                swap_times.append(time.monotonic() - started)
                swap_windows.append((started, time.monotonic()))

        thread = threading.Thread(target=swapper)
        thread.start()
        replies: list[float] = []
        pose, velocity = PoseStamped(), Twist()
        next_tick = time.monotonic()
        while thread.is_alive() or (time.monotonic() < next_tick + 1.0 and len(replies) < 10):
            try:
                client.compute_velocity_commands(pose, velocity)
                replies.append(time.monotonic())
            except Nav2Error as exc:
                failures.append(f"{type(exc).__name__}: {exc}")
            next_tick += period
            time.sleep(max(0.0, next_tick - time.monotonic()))
        thread.join()
        # A gap "during a swap" ends inside a swap window (or just after it); the others
        # show the loop's own scheduling jitter on this machine, the baseline to compare with.
        during: list[float] = []
        outside: list[float] = []
        for a, b in itertools.pairwise(replies):
            in_swap = any(start <= b <= end + 2 * period for start, end in swap_windows)
            (during if in_swap else outside).append(b - a)
        client.close()
        session.close()
    return {
        "swaps": swaps,
        "calls": len(replies) + len(failures),
        "failed_calls": len(failures),
        "failures": failures[:5],
        "longest_gap_ms": 1000 * max(during + outside),
        "longest_gap_during_swaps_ms": 1000 * max(during, default=0.0),
        "longest_gap_without_swap_ms": 1000 * max(outside, default=0.0),
        "period_ms": 1000 * period,
        "resyncs": client.resyncs,
        "swap_duration_median_s": float(np.median(swap_times)),
    }


def _rss_kb(pid: int) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    return 0


def _family(pid: int) -> list[int]:
    children = Path(f"/proc/{pid}/task/{pid}/children").read_text().split()
    return [pid, *(int(c) for c in children)]


def endurance(calls: int, lifecycle_cycles: int) -> dict[str, Any]:
    """RSS of the host and its worker over ``calls`` control cycles; a line fit gives the
    growth per 100k calls after warm-up. Then ``lifecycle_cycles`` configure -> activate ->
    deactivate -> cleanup cycles (the planner imports NumPy)."""
    with PlannerHostProcess([{"key": KEY, "planner": V1}]) as host:
        assert host.proc is not None
        session = open_session([host.endpoint])
        client = _client(session, host)
        client.configure()
        client.activate()
        client.set_plan(Plan(np.zeros((200, 3)), "odom"))
        pose, velocity = PoseStamped(), Twist()
        samples: list[tuple[int, int]] = []
        step = max(1, calls // 40)
        started = time.monotonic()
        for i in range(calls):
            client.compute_velocity_commands(pose, velocity)
            if i % step == 0:
                samples.append((i, sum(_rss_kb(p) for p in _family(host.proc.pid))))
                print(
                    f"  … {i:>8} calls, host + worker RSS {samples[-1][1] / 1024:.1f} MiB",
                    flush=True,
                )
        elapsed = time.monotonic() - started
        warm = samples[len(samples) // 5 :]
        x, y = np.array([s[0] for s in warm], float), np.array([s[1] for s in warm], float)
        slope_kb_per_100k = float(np.polyfit(x, y, 1)[0] * 100_000) if len(x) > 2 else 0.0
        client.deactivate()
        client.cleanup()
        for _ in range(10):  # warm-up: allocator pools and Zenoh buffers settle
            client.configure()
            client.cleanup()
        before = sum(_rss_kb(p) for p in _family(host.proc.pid))
        for _ in range(lifecycle_cycles):
            client.configure()
            client.activate()
            client.compute_velocity_commands(pose, velocity)
            client.deactivate()
            client.cleanup()
        after = sum(_rss_kb(p) for p in _family(host.proc.pid))
        client.close()
        session.close()
    return {
        "calls": calls,
        "seconds": elapsed,
        "calls_per_s": calls / elapsed,
        "rss_start_mib": samples[0][1] / 1024,
        "rss_end_mib": samples[-1][1] / 1024,
        "slope_kib_per_100k_calls": slope_kb_per_100k,
        "lifecycle_cycles": lifecycle_cycles,
        "lifecycle_rss_before_mib": before / 1024,
        "lifecycle_rss_after_mib": after / 1024,
    }


def run(args: argparse.Namespace) -> dict[str, Any]:
    print(f"  … hot swap: {args.swaps} swaps under a 20 Hz loop", flush=True)
    results = {"hot_swap": hot_swap(args.swaps)}
    print(f"  … endurance: {args.calls} calls, then {args.cycles} lifecycle cycles", flush=True)
    results["endurance"] = endurance(args.calls, args.cycles)
    return results


def report(results: dict[str, Any]) -> str:
    h, e = results["hot_swap"], results["endurance"]
    return "\n".join(
        [
            "hot swap (V1 <-> V2 on a live key, client calling at 20 Hz, 50 ms call timeout)",
            f"  swaps {h['swaps']}, calls {h['calls']}, failed calls {h['failed_calls']}, "
            f"longest gap between replies {h['longest_gap_during_swaps_ms']:.0f} ms during "
            f"swaps, {h['longest_gap_without_swap_ms']:.0f} ms without "
            f"(period {h['period_ms']:.0f} ms), client re-syncs {h['resyncs']}, "
            f"swap takes {h['swap_duration_median_s']:.2f} s (median, in the background)",
            "",
            f"endurance: {e['calls']} control cycles in {e['seconds']:.0f} s "
            f"({e['calls_per_s']:.0f}/s), host + worker RSS {e['rss_start_mib']:.1f} -> "
            f"{e['rss_end_mib']:.1f} MiB, fitted slope {e['slope_kib_per_100k_calls']:+.1f} KiB "
            "per 100k calls after warm-up",
            f"lifecycle: {e['lifecycle_cycles']} configure/activate/deactivate/cleanup cycles "
            f"(after 10 warm-up), RSS {e['lifecycle_rss_before_mib']:.1f} -> "
            f"{e['lifecycle_rss_after_mib']:.1f} MiB",
        ]
    )
