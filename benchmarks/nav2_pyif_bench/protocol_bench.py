"""The protocol's cost, beside the bare Zenoh floor and the rclpy-node workaround, all
measured in one run with interleaved rounds (so drift hits all alike).

    nav2-pyif-bench protocol            # about a minute; prints the tables of BENCHMARKS.md
    nav2-pyif-bench protocol --quick    # a smoke run
"""

from __future__ import annotations

import argparse
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import asdict
from typing import Any

import numpy as np
import zenoh
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif import Costmap, Plan
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.option_types import non_negative_int, positive_float, positive_int
from nav2_pyif.common.zenoh_config import connect_to
from nav2_pyif_protocol.codec import Request, encode_request
from nav2_pyif_protocol.constants import Op
from nav_msgs.msg import Odometry

from nav2_pyif_bench.processes import free_port, peer_processes, ros_localhost_env
from nav2_pyif_bench.rclpy_client import RclpyWorkaroundClient, path_message
from nav2_pyif_bench.stats import Summary, cycle_target_lines, header_row, verdict

KEY = "nav2_pyif/bench/FollowPath"
INPROC_KEY = "nav2_pyif/bench/InProcess"
BARE_KEY = "nav2_pyif/bench/bare"
TIMEOUTS = Timeouts(call=2.0, lifecycle=5.0, configure=10.0)


def progress(message: str) -> None:
    print(f"  … {message}", file=sys.stderr, flush=True)


def costmap(size: int, version: int = 1) -> Costmap:
    grid = np.zeros((size, size), np.uint8)
    grid[::7, ::5] = Costmap.LETHAL
    return Costmap(grid, 0.05, -10.0, -10.0, "odom", version=version)


open_session = connect_to  # the benchmarks' sessions: plain peers on loopback


def timed_get(session: zenoh.Session, key: str, payload: bytes) -> int:
    """Round trip [ns] of one get answered by one reply."""
    start = time.perf_counter_ns()
    for reply in session.get(key, payload=payload, timeout=2.0):
        if reply.ok is None:
            raise TimeoutError(f"nothing answered {key}")
        break
    return time.perf_counter_ns() - start


def bare_get(session: zenoh.Session) -> int:
    return timed_get(session, BARE_KEY, b"")


def host_floor(session: zenoh.Session, payload: bytes) -> int:
    """A request the host answers with its cheapest reply (SessionUnknown): the host's fixed
    cost per query (decode, session look-up, encode) without any planner or message work."""
    return timed_get(session, f"{KEY}/rpc/activate", payload)


def timed(call: Callable[[], Any]) -> int:
    start = time.perf_counter_ns()
    call()
    return time.perf_counter_ns() - start


def interleaved(
    methods: dict[str, Callable[[], int]], rounds: int, per_round: int, stage: str
) -> dict[str, list[int]]:
    samples: dict[str, list[int]] = {name: [] for name in methods}
    for method in methods.values():  # warm-up
        for _ in range(min(50, per_round)):
            method()
    for r in range(rounds):
        progress(f"{stage}: round {r + 1}/{rounds}")
        for name, method in methods.items():
            samples[name] += [method() for _ in range(per_round)]
    return samples


def paced(rows: dict[str, Callable[[], int]], calls: int, rate: float) -> dict[str, list[int]]:
    """Each row once per period, the rows' calls evenly spread over it: calls as Nav2 makes
    them, each after an idle gap, so each pays what the gap costs (caches gone cold, threads
    to wake) and a tight loop never does."""
    period = 1.0 / rate
    slot = period / len(rows)
    samples: dict[str, list[int]] = {name: [] for name in rows}
    progress(f"at {rate:g} Hz: {calls} calls per row")
    start = time.monotonic() + period
    for i in range(calls):
        for k, (name, row) in enumerate(rows.items()):
            time.sleep(max(0.0, start + i * period + k * slot - time.monotonic()))
            samples[name].append(row())
    return samples


def first_of_each_round(samples: list[int], per_round: int) -> tuple[list[int], list[int]]:
    """The first call of each round, and the others. A round's first plan follows the rclpy
    row's (19 ms each of DDS work in two processes) and runs cold: about 2 ms where the rest
    take 0.8. A run of few plans per round is mostly first calls, and its median misleads."""
    first = samples[::per_round]
    rest = [s for i, s in enumerate(samples) if i % per_round]
    return first, rest


def throughput(session: zenoh.Session, threads: int, seconds: float) -> float:
    clients = [
        ControllerClient(session, KEY, costmap(10), timeouts=TIMEOUTS) for _ in range(threads)
    ]
    for client in clients:
        client.wait_for_host(10)
        client.configure()
    counts = [0] * threads
    stop = threading.Event()
    pose, velocity = PoseStamped(), Twist()

    def run(i: int) -> None:
        while not stop.is_set():
            clients[i].compute_velocity_commands(pose, velocity)
            counts[i] += 1

    workers = [threading.Thread(target=run, args=(i,)) for i in range(threads)]
    start = time.perf_counter()
    for w in workers:
        w.start()
    time.sleep(seconds)
    stop.set()
    for w in workers:
        w.join()
    elapsed = time.perf_counter() - start
    for client in clients:
        client.cleanup()
        client.close()
    return sum(counts) / elapsed


def peer_commands(host_port: int, inproc_port: int, bare_port: int) -> dict[str, list[str]]:
    """The cycle's peers, as arguments of the project's Python: the planner host (worker
    process), the in-process planner host, the bare queryable and the rclpy node."""

    def host(port: int, key: str, *extra: str) -> list[str]:
        return [
            "-m",
            "nav2_pyif.server.cli",
            "--listen",
            f"tcp/127.0.0.1:{port}",
            "--key",
            key,
            "--planner",
            "nav2_pyif_bench.planners:TrivialController",
            "--log-level",
            "WARNING",
            *extra,
        ]

    return {
        "host": host(host_port, KEY),
        "inproc": host(inproc_port, INPROC_KEY, "--isolation", "none"),
        "bare": [
            "-m",
            "nav2_pyif_bench.bare_zenoh",
            "--listen",
            f"tcp/127.0.0.1:{bare_port}",
            "--key",
            BARE_KEY,
        ],
        "rclpy": ["-m", "nav2_pyif_bench.rclpy_node"],
    }


def run(args: argparse.Namespace) -> dict[str, Any]:
    host_port, bare_port, inproc_port = free_port(), free_port(), free_port()
    env = ros_localhost_env()
    commands = peer_commands(host_port, inproc_port, bare_port)
    import os

    os.environ.update(env)
    results: dict[str, Any] = {}
    with peer_processes(commands, env) as peers:
        session = open_session(
            [f"tcp/127.0.0.1:{port}" for port in (host_port, bare_port, inproc_port)]
        )
        ros = RclpyWorkaroundClient()
        client = ControllerClient(session, KEY, costmap(10), timeouts=TIMEOUTS, record_calls=True)
        try:
            progress("waiting for the planner host, the bare queryable and the rclpy node")
            if not client.wait_for_host(30):
                raise peers.not_up("the planner host")
            client.configure()
            client.activate()
            inproc = ControllerClient(session, INPROC_KEY, costmap(10), timeouts=TIMEOUTS)
            if not inproc.wait_for_host(30):
                raise peers.not_up("the in-process planner host")
            inproc.configure()
            inproc.activate()
            deadline = time.monotonic() + 30
            while True:
                try:
                    bare_get(session)
                    break
                except TimeoutError:
                    if time.monotonic() > deadline:
                        raise
            if not ros.wait_ready():
                raise peers.not_up("the rclpy node (DDS discovery)")

            pose, velocity, odom = PoseStamped(), Twist(), Odometry()
            pose.header.frame_id = odom.header.frame_id = "odom"
            unknown = encode_request(Request(Op.ACTIVATE, "not-a-session", 1, 1, {}))
            cycle = interleaved(
                {
                    "bare": lambda: bare_get(session),
                    "host_floor": lambda: host_floor(session, unknown),
                    "pyif": lambda: timed(lambda: client.compute_velocity_commands(pose, velocity)),
                    "pyif_inproc": lambda: timed(
                        lambda: inproc.compute_velocity_commands(pose, velocity)
                    ),
                    "rclpy": lambda: ros.cycle(odom),
                },
                args.rounds,
                args.calls,
                "control cycle",
            )
            assert client.records is not None
            handler = [r.compute_ns for r in client.records if r.op == "compute_velocity_commands"]
            results["cycle"] = {k: asdict(Summary.of_ns(v)) for k, v in cycle.items()}
            results["cycle"]["host_handler"] = asdict(Summary.of_ns(handler))

            plan = Plan(
                np.column_stack([np.arange(1000) * 0.05, np.zeros(1000), np.zeros(1000)]), "odom"
            )
            path_msg = path_message(1000)
            plans = interleaved(
                {
                    "pyif": lambda: timed(lambda: client.set_plan(plan)),
                    "rclpy": lambda: ros.send_plan(path_msg),
                },
                max(1, args.rounds // 2),
                args.plan_calls,
                "1000-pose plan",
            )
            results["plan_1000"] = {k: asdict(Summary.of_ns(v)) for k, v in plans.items()}
            first, rest = first_of_each_round(plans["pyif"], args.plan_calls)
            results["plan_1000"]["pyif_first_of_round"] = asdict(Summary.of_ns(first))
            if rest:
                results["plan_1000"]["pyif_rest_of_round"] = asdict(Summary.of_ns(rest))
            handled = [r.compute_ns for r in client.records if r.op == "set_plan"]
            results["plan_1000"]["host_handler"] = asdict(Summary.of_ns(handled))
            at_rate = paced(
                {
                    "bare": lambda: bare_get(session),
                    "cycle": lambda: timed(
                        lambda: client.compute_velocity_commands(pose, velocity)
                    ),
                    "plan": lambda: timed(lambda: client.set_plan(plan)),
                },
                args.paced_calls,
                args.rate,
            )
            results["paced"] = {k: asdict(Summary.of_ns(v)) for k, v in at_rate.items()}
            results["rate"] = args.rate

            costmap_400 = costmap(400, version=100)
            versions = iter(range(101, 10**9))

            def changed() -> int:
                client.update_costmap(
                    Costmap(
                        costmap_400.data,
                        costmap_400.resolution,
                        costmap_400.origin_x,
                        costmap_400.origin_y,
                        costmap_400.frame_id,
                        version=next(versions),
                    )
                )
                return timed(lambda: client.compute_velocity_commands(pose, velocity))

            def unchanged() -> int:
                return timed(lambda: client.compute_velocity_commands(pose, velocity))

            client.update_costmap(costmap_400)
            client.compute_velocity_commands(pose, velocity)
            maps = interleaved(
                {"changed": changed, "unchanged": unchanged},
                max(1, args.rounds // 2),
                args.costmap_calls,
                "400x400 costmap",
            )
            # "unchanged" after "changed" in the same round: the first unchanged call of each
            # round still carries the map, so take bytes from the records directly.
            sent = [r.request_bytes for r in client.records[-2 * args.costmap_calls :]]
            results["costmap_400"] = {k: asdict(Summary.of_ns(v)) for k, v in maps.items()}
            results["costmap_400"]["request_bytes_changed"] = max(sent)
            results["costmap_400"]["request_bytes_unchanged"] = min(sent)

            client.update_costmap(costmap(10, version=10**9 + 1))
            results["throughput"] = {}
            for threads in args.threads:
                progress(f"throughput with {threads} client thread(s), {args.seconds} s")
                results["throughput"][str(threads)] = throughput(session, threads, args.seconds)
        finally:
            client.close()
            ros.close()
            session.close()
    return results


def report(results: dict[str, Any]) -> str:
    def summary(d: dict[str, Any]) -> Summary:
        return Summary(**d)

    lines = []
    c = {k: summary(v) for k, v in results["cycle"].items()}
    lines += [
        "control cycle: PoseStamped + Twist in, TwistStamped out (trivial planner)",
        header_row(),
        c["bare"].row("bare Zenoh get -> empty reply"),
        c["host_floor"].row("host's cheapest reply (SessionUnknown)"),
        c["pyif"].row("nav2_pyif cycle, worker process (default)"),
        c["pyif_inproc"].row("nav2_pyif cycle, --isolation none"),
        c["host_handler"].row("  of which host handler (decode..encode)"),
        c["rclpy"].row("rclpy node over topics (workaround)"),
    ]
    isolation = c["pyif"].median_us - c["pyif_inproc"].median_us
    lines += cycle_target_lines(
        c["bare"].median_us,
        c["rclpy"].median_us,
        {"--isolation none": c["pyif_inproc"].median_us, "worker process": c["pyif"].median_us},
    )
    lines += [f"  the worker process (crash isolation) adds {isolation:+.1f} µs median", ""]
    p = {k: summary(v) for k, v in results["plan_1000"].items()}
    lines += [
        "1000-pose plan reaching the planner as NumPy (N, 3)",
        header_row(),
        p["pyif"].row("nav2_pyif set_plan"),
        *(
            [p["host_handler"].row("  of which host handler (decode..planner)")]
            if "host_handler" in p
            else []
        ),
        *(
            p[key].row(label)
            for key, label in (
                ("pyif_first_of_round", "  first of each round (after rclpy's row)"),
                ("pyif_rest_of_round", "  the rest of each round"),
            )
            if key in p
        ),
        p["rclpy"].row("rclpy node, nav_msgs/Path topic"),
        f"  target <= 1 ms: {verdict(p['pyif'].median_us, '<=', 1000, 1)}",
        f"  over this run's control cycle (worker process): "
        f"{p['pyif'].median_us - c['pyif'].median_us:+.1f} µs median (the plan's own cost; "
        "the round trip's floor is the cycle's: compare the two on one machine state)",
        "",
    ]
    if "paced" in results:
        paced_rows = {k: summary(v) for k, v in results["paced"].items()}
        lines += paced_lines(paced_rows, results["rate"], c["bare"], c["pyif"], p["pyif"])
    m = results["costmap_400"]
    lines += [
        "400 x 400 costmap with a control cycle",
        header_row(),
        summary(m["changed"]).row(f"changed: sent ({m['request_bytes_changed']} B request)"),
        summary(m["unchanged"]).row(
            f"unchanged: not sent ({m['request_bytes_unchanged']} B request)"
        ),
        f"  target <= 1 ms when changed: {verdict(summary(m['changed']).median_us, '<=', 1000, 1)}",
        "",
    ]
    lines += ["host throughput, trivial planner, one key, N client sessions in one process"]
    lines += [
        f"  {n} client thread(s): {rate:,.0f} calls/s" for n, rate in results["throughput"].items()
    ]
    return "\n".join(lines)


def paced_lines(
    rows: dict[str, Summary], rate: float, bare: Summary, cycle: Summary, plan: Summary
) -> list[str]:
    """The paced rows beside the tight loop's: what each call costs after an idle gap."""
    labels = {
        "bare": ("bare Zenoh get -> empty reply", bare),
        "cycle": ("nav2_pyif cycle, worker process", cycle),
        "plan": ("nav2_pyif set_plan, 1000 poses", plan),
    }
    lines = [
        f"the same calls at {rate:g} Hz (each row once a period, spread over it: as Nav2 paces "
        "them)",
        f"{header_row()} {'tight µs':>10}",
    ]
    lines += [
        f"{rows[k].row(label)} {tight.median_us:>10.1f}" for k, (label, tight) in labels.items()
    ]
    lines += [
        f"  set_plan at {rate:g} Hz: target <= 1 ms: "
        f"{verdict(rows['plan'].median_us, '<=', 1000, 1)}; over the paced cycle "
        f"{rows['plan'].median_us - rows['cycle'].median_us:+.1f} µs median; the gap costs the "
        f"bare get {rows['bare'].median_us - bare.median_us:+.1f} µs over the tight one",
        "",
    ]
    return lines


def _rounds(parser: argparse.ArgumentParser, calls: str) -> None:
    parser.add_argument(
        "--rounds", type=positive_int, default=10, help="interleaved rounds, >= 1 (default 10)"
    )
    parser.add_argument(
        "--calls", type=positive_int, default=300, help=f"{calls}, >= 1 (default 300)"
    )
    parser.add_argument("--quick", action="store_true", help="a short smoke run")


def add_rounds_and_rate(
    parser: argparse.ArgumentParser, *, paced_calls: int, none_paced: bool
) -> None:
    """Interleaved rounds, then paced calls at --rate, and --quick: the C++ cycle's and the
    hops' options (``none_paced``: --paced-calls 0 skips the paced rows)."""
    _rounds(parser, "calls per row and round")
    least = ">= 0 (0: none; " if none_paced else ">= 1 ("
    parser.add_argument(
        "--paced-calls",
        type=non_negative_int if none_paced else positive_int,
        default=paced_calls,
        help=f"then this many calls per row at --rate, {least}default {paced_calls})",
    )
    parser.add_argument(
        "--rate",
        type=positive_float,
        default=20.0,
        help="the paced rows' rate [Hz], > 0 (default 20)",
    )


def add_round_arguments(parser: argparse.ArgumentParser) -> None:
    """Rounds of control cycles and plans, and --quick: this benchmark's and the TLS one's."""
    _rounds(parser, "control cycles per round")
    parser.add_argument(
        "--plan-calls", type=positive_int, default=40, help="plans per round, >= 1 (default 40)"
    )


def apply_quick_rounds(args: argparse.Namespace) -> argparse.Namespace:
    if args.quick:
        # 20 plans, not 5: the first of a round runs cold (first_of_each_round), and with 5
        # the quick median read 1.02-1.07 ms where full runs read 0.80-0.83.
        args.rounds, args.calls, args.plan_calls = 2, 50, 20
    return args


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_round_arguments(parser)
    parser.add_argument(
        "--paced-calls",
        type=positive_int,
        default=100,
        help="then this many bare gets, cycles and plans at --rate, >= 1 (default 100)",
    )
    parser.add_argument(
        "--rate", type=positive_float, default=20.0, help="the paced rows' rate [Hz] (default 20)"
    )
    parser.add_argument(
        "--costmap-calls",
        type=positive_int,
        default=100,
        help="cycles per round with a new costmap each, >= 1 (default 100)",
    )
    parser.add_argument(
        "--threads",
        type=positive_int,
        nargs="+",
        default=[1, 4],
        help="client threads of each throughput run, each >= 1 (default 1 4)",
    )
    parser.add_argument(
        "--seconds",
        type=positive_float,
        default=3.0,
        help="seconds per throughput run, > 0 (default 3)",
    )


def apply_quick(args: argparse.Namespace) -> argparse.Namespace:
    if args.quick:
        args.costmap_calls, args.seconds, args.paced_calls = 10, 0.5, 20
    return apply_quick_rounds(args)
