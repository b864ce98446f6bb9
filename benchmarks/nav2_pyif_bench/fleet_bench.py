"""Many robots, one planner host: N controller keys served by one host, N clients calling at
20 Hz from several client processes. Per-robot workers (the default: one worker process per
key) or ``--batch`` (one worker for all keys, their cycles batched). Reports the latency, the
missed periods (no valid reply within the 50 ms period) and the CPU the host and its workers
used, to show where the 2-core limit is."""

from __future__ import annotations

import argparse
import multiprocessing
import os
import shutil
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

from nav2_pyif_bench.fleet_planners import (
    FleetPlanner,
    costmap,
    fleet_planner,
    plan,
    robot_pose,
    scan,
    workdir,
)

PERIOD = 0.05


def key(i: int) -> str:
    return f"nav2_pyif/robot{i}/FollowPath"


def _robot(
    endpoint_session: Any,
    index: int,
    planner: FleetPlanner,
    seconds: float,
    out: list[tuple[float, bool]],
    errors: list[str],
    ready: Any,
    go: Any,
) -> None:
    from geometry_msgs.msg import Twist
    from nav2_pyif.client import ControllerClient, Timeouts
    from nav2_pyif.exceptions import Nav2Error

    client = ControllerClient(
        endpoint_session,
        key(index),
        costmap(),
        params=planner.params,
        timeouts=Timeouts(call=10.0, lifecycle=60, configure=300),
    )
    cycles = round(seconds / PERIOD)
    try:
        client.wait_for_host(300)
        client.configure()  # dozens of robots set up at once: generous timeouts
        client.activate()
        client.set_plan(plan())
        _warm_up(client, planner)
    except Nav2Error as exc:  # never set up: every cycle of its run is a miss
        out.extend([(PERIOD, False)] * cycles)
        errors.append(f"set-up failed: {exc}")
        client.close()
        return
    finally:
        ready.put(index)
    client.timeouts = Timeouts(call=PERIOD, lifecycle=30, configure=60)  # the control loop
    pose, velocity = robot_pose(), Twist()
    go.wait()
    start_at = go.start_at.value
    time.sleep(max(0.0, start_at - time.monotonic()))
    next_tick = start_at + (index % 20) * PERIOD / 20  # spread robots over a period
    for _ in range(cycles):
        time.sleep(max(0.0, next_tick - time.monotonic()))
        started = time.perf_counter()
        try:
            client.compute_velocity_commands(pose, velocity, inputs=_inputs(planner))
            out.append((time.perf_counter() - started, True))
        except Nav2Error as exc:
            out.append((time.perf_counter() - started, False))
            errors.append(str(exc).splitlines()[0])
        next_tick += PERIOD
    client.close()


def _warm_up(client: Any, planner: FleetPlanner, within: float = 300.0) -> None:
    """One cycle that works: dozens of workers warming up at once may overrun a deadline."""
    from geometry_msgs.msg import Twist
    from nav2_pyif.exceptions import Nav2Error

    deadline = time.monotonic() + within
    while True:
        try:
            client.compute_velocity_commands(robot_pose(), Twist(), inputs=_inputs(planner))
            return
        except Nav2Error:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.5)


def _inputs(planner: FleetPlanner) -> dict[str, tuple[Any, int]] | None:
    """A new scan with every cycle, as a 20 Hz laser gives one (the learned controller)."""
    return {"scan": (scan(), time.time_ns())} if planner.scan else None


class _Go:
    """When to start, for every client process: an event and the start time."""

    def __init__(self, ctx: Any) -> None:
        self.event = ctx.Event()
        self.start_at = ctx.Value("d", 0.0)

    def wait(self) -> None:
        self.event.wait()


def _client_process(
    endpoint: str,
    indices: list[int],
    planner: FleetPlanner,
    seconds: float,
    ready: Any,
    go: _Go,
    queue: Any,
) -> None:
    from nav2_pyif_bench.protocol_bench import open_session

    session = open_session([endpoint])
    results: list[tuple[float, bool]] = []
    errors: list[str] = []
    threads = [
        threading.Thread(
            target=_robot, args=(session, i, planner, seconds, results, errors, ready, go)
        )
        for i in indices
    ]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    session.close()
    queue.put((results, errors))


def _cpu_seconds(pid: int) -> float:
    """utime + stime of a process and its children (the workers), from /proc."""
    ticks = os.sysconf("SC_CLK_TCK")
    total = 0.0
    children = Path(f"/proc/{pid}/task/{pid}/children").read_text().split()
    for p in [pid, *map(int, children)]:
        fields = Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()
        total += (int(fields[11]) + int(fields[12])) / ticks
    return total


def _batching(endpoint: str) -> dict[str, Any]:
    """The batch group's counts, as ``nav2-pyif hosts`` shows them."""
    from nav2_pyif.client.hosts import ask_info

    from nav2_pyif_bench.protocol_bench import open_session

    session = open_session([endpoint])
    try:
        answers = ask_info(session, {key(0)}, timeout=5.0)
    finally:
        session.close()
    info = next(iter(answers.values()), {})
    batch: dict[str, Any] = info.get("batch", {})
    return batch


def host_arguments(args: argparse.Namespace, batched: bool) -> list[str]:
    extra = ["--isolation", args.isolation]
    if batched:
        extra += ["--batch", "--batch-window", f"{args.batch_window:g}"]
    return extra


#: one thread per XLA computation: no thread pool spinning on the cores the clients need
XLA_SINGLE_THREAD = "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1"


def host_env(args: argparse.Namespace) -> dict[str, str]:
    return {"XLA_FLAGS": XLA_SINGLE_THREAD} if args.xla_single_thread else {}


def run_one(args: argparse.Namespace, robots: int, batched: bool) -> dict[str, Any]:
    from nav2_pyif.common.host_process import PlannerHostProcess

    directory = workdir()
    try:
        planner = fleet_planner(args.planner, robots, args.rollouts, directory)
        entries = [{"key": key(i), "planner": planner.spec} for i in range(robots)]
        host = PlannerHostProcess(entries, args=host_arguments(args, batched), env=host_env(args))
        with host:
            assert host.proc is not None
            drive = _cpp_clients if args.cpp_clients else _python_clients
            samples, errors, cores = drive(args, host, robots, planner)
            batching = _batching(host.endpoint) if batched else {}
    finally:
        shutil.rmtree(directory, ignore_errors=True)
    return _summary(args, robots, batched, samples, errors, cores, batching)


Driven = tuple[list[tuple[float, bool]], list[str], float]


def _python_clients(
    args: argparse.Namespace, host: Any, robots: int, planner: FleetPlanner
) -> Driven:
    """The robots as Python reference clients in up to 4 processes: samples, errors, and the
    cores the host and its workers used meanwhile."""
    ctx = multiprocessing.get_context("spawn")
    queue, ready, go = ctx.Queue(), ctx.Queue(), _Go(ctx)
    processes = min(robots, 4)
    groups = [list(range(robots))[g::processes] for g in range(processes)]
    clients = [
        ctx.Process(
            target=_client_process,
            args=(host.endpoint, g, planner, args.seconds, ready, go, queue),
        )
        for g in groups
    ]
    try:
        for c in clients:
            c.start()
        for _ in range(robots):  # every robot configured, compiled and warm
            ready.get(timeout=600)
        go.start_at.value = time.monotonic() + 1.0
        go.event.set()
        time.sleep(max(0.0, go.start_at.value - time.monotonic()))
        cpu_before, wall_before = _cpu_seconds(host.proc.pid), time.monotonic()
        samples: list[tuple[float, bool]] = []
        errors: list[str] = []
        for _ in clients:
            got, failed = queue.get(timeout=args.seconds + 300)
            samples, errors = samples + got, errors + failed
        cores = (_cpu_seconds(host.proc.pid) - cpu_before) / (time.monotonic() - wall_before)
        for c in clients:
            c.join(30)
    finally:  # also on a signal or an error: no client process is left behind
        for c in clients:
            if c.pid is not None and c.is_alive():
                c.terminate()
                c.join(5)
    return samples, errors, cores


def _cpp_clients(args: argparse.Namespace, host: Any, robots: int, planner: FleetPlanner) -> Driven:
    """The robots as the plugin's C++ client code (fleet_cpp_clients), as _python_clients."""
    from nav2_pyif_bench.fleet_cpp_clients import client_binary, run_cpp_clients

    start: list[tuple[float, float]] = []

    def on_go(at: float) -> None:
        time.sleep(max(0.0, at - time.monotonic()))
        start.append((_cpu_seconds(host.proc.pid), time.monotonic()))

    binary = client_binary(args.fleet_client)
    samples, errors = run_cpp_clients(
        host.endpoint, robots, planner, args.seconds, PERIOD, binary, args.setup, on_go
    )
    cpu_before, wall_before = start[0]
    cores = (_cpu_seconds(host.proc.pid) - cpu_before) / (time.monotonic() - wall_before)
    return samples, errors, cores


def _summary(
    args: argparse.Namespace,
    robots: int,
    batched: bool,
    samples: list[tuple[float, bool]],
    errors: list[str],
    host_cores: float,
    batching: dict[str, Any],
) -> dict[str, Any]:
    latency = np.array([s[0] for s in samples if s[1]]) * 1000
    missed = sum(1 for s in samples if not s[1] or s[0] > PERIOD)
    return {
        "robots": robots,
        "calls": len(samples),
        "calls_per_s": len(samples) / args.seconds,
        "median_ms": float(np.median(latency)) if len(latency) else float("nan"),
        "p99_ms": float(np.percentile(latency, 99)) if len(latency) else float("nan"),
        "missed": missed,
        "missed_pct": 100.0 * missed / max(1, len(samples)),
        "host_cpu_cores": host_cores,
        "isolation": args.isolation,
        "planner": args.planner,
        "mode": _mode(args, batched) + (", C++ clients" if args.cpp_clients else ""),
        "errors": sorted(set(errors))[:5],  # what the failed calls said
        "xla_single_thread": bool(args.xla_single_thread),
        # the whole run's, set-up included: robots per batched call, cycles not computed
        "cycles_per_batch": batching.get("cycles", 0) / max(1, batching.get("batches", 0)),
        "dropped": batching.get("dropped", 0),
        "superseded": batching.get("superseded", 0),
    }


def _mode(args: argparse.Namespace, batched: bool) -> str:
    if batched:
        return f"batched ({args.batch_window:g} ms window)"
    return "one worker each" if args.isolation == "process" else "no workers: --isolation none"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Each fleet size in each mode (per-robot workers, batched, or both with --compare);
    with --stop-at-miss, a mode stops at its first size that missed a period."""
    modes = [False, True] if args.compare else [args.batch]
    if args.cpp_clients:  # before anything starts: say how to build it
        from nav2_pyif_bench.cpp_cycle_bench import setup_script
        from nav2_pyif_bench.fleet_cpp_clients import client_binary

        client_binary(args.fleet_client)
        setup_script(args.setup)
    results: dict[str, Any] = {}
    for batched in modes:
        sizes = (args.batch_robots if batched and args.compare else None) or args.robots
        for n in sizes:
            label = _mode(args, batched)
            print(f"  … {n} robot(s) at 20 Hz for {args.seconds:g} s ({label})", flush=True)
            result = run_one(args, n, batched)
            results[f"{label}/{n}"] = result
            if args.stop_at_miss and result["missed"]:
                break
    return results


def report(results: dict[str, Any]) -> str:
    first = next(iter(results.values()), {"planner": "trivial"})
    lines = [
        f"fleet: N controllers on one host ({first['planner']} planner), clients at 20 Hz",
        f"  {'mode':<36} {'robots':>6} {'calls/s':>8} {'median':>9} {'p99':>9} "
        f"{'missed':>14} {'host CPU':>11}",
    ]
    for r in results.values():
        lines.append(
            f"  {r['mode']:<36} {r['robots']:>6} {r['calls_per_s']:>8.0f} "
            f"{r['median_ms']:>6.2f} ms {r['p99_ms']:>6.2f} ms "
            f"{r['missed']:>7} ({r['missed_pct']:4.1f} %) "
            f"{r['host_cpu_cores']:>5.2f} cores"
        )
    for r in results.values():
        if r["cycles_per_batch"]:
            lines.append(
                f"  {r['mode']}, {r['robots']} robots: {r['cycles_per_batch']:.1f} cycles per "
                f"batched call, not computed: {r['dropped']} (waited a whole period), "
                f"{r.get('superseded', 0)} (superseded by the robot's next cycle)"
            )
        for error in r["errors"][:2]:
            lines.append(f"  {r['mode']}, {r['robots']} robots: {error}")
    for mode in dict.fromkeys(r["mode"] for r in results.values()):
        served = [r["robots"] for r in results.values() if r["mode"] == mode and not r["missed"]]
        lines.append(
            f"  {mode}: most robots served with no missed period: {max(served, default=0)}"
        )
    lines.append("  missed: no valid reply within the 50 ms control period")
    return "\n".join(lines)
