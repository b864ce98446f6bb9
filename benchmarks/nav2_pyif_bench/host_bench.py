"""The control cycle against a planner host that is already running, wherever it is: what a
robot would see from a deployed host (a GPU box, a container, through the fleet router).

The client is the reference client, the plugin's Python twin, in the plugin's Zenoh mode
(client, unless --mode says otherwise): a controller session on --key with a synthetic
costmap and a straight plan ahead, then --calls compute_velocity_commands at --rate Hz (0:
back to back), then deactivate and cleanup. The planner runs with its default parameters.

    nav2-pyif-bench host --connect tcp/192.168.1.20:7447 --key nav2_pyif/robot1/FollowPath
"""

from __future__ import annotations

import argparse
import math
import time
from typing import Any

import numpy as np
from geometry_msgs.msg import Twist
from nav2_pyif import Plan
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.client.hosts import visible_hosts
from nav2_pyif.common.option_types import non_negative_float, positive_int
from nav2_pyif.common.zenoh_config import ZenohOptions, add_endpoint_arguments, open_session

from nav2_pyif_bench.protocol_bench import costmap, progress
from nav2_pyif_bench.stats import Summary, header_row

TIMEOUTS = Timeouts(call=2.0, lifecycle=5.0, configure=30.0)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--key", required=True, help="the key prefix a controller is served on")
    add_endpoint_arguments(
        p,
        config_help="a JSON5 Zenoh config instead",
        connect_help="the router or host to connect to, repeatable",
        listen_help="endpoint to listen on, repeatable (peers dial it)",
    )
    p.add_argument(
        "--mode",
        choices=["client", "peer"],
        default="client",
        help="this session's Zenoh mode (default client, as the C++ plugin)",
    )
    p.add_argument(
        "--calls", type=positive_int, default=2000, help="control cycles, >= 1 (default 2000)"
    )
    p.add_argument(
        "--rate",
        type=non_negative_float,
        default=20.0,
        help="calls per second, >= 0 (0: unpaced; default 20)",
    )
    p.add_argument(
        "--wait",
        type=non_negative_float,
        default=10.0,
        metavar="SECONDS",
        help="seconds to wait for the host, >= 0 (default 10)",
    )


def _pose(x: float, y: float) -> Any:
    from nav2_pyif.runner.run import pose_msg

    return pose_msg(x, y, 0.0, frame="odom")


def run(args: argparse.Namespace) -> dict[str, Any]:
    options = ZenohOptions(args.zenoh_config, list(args.connect), list(args.listen), args.mode)
    try:
        session = open_session(options)
    except (ConnectionError, FileNotFoundError) as exc:
        raise SystemExit(f"nav2-pyif-bench host: {exc}") from None
    client = ControllerClient(session, args.key, costmap(200), timeouts=TIMEOUTS)
    try:
        if not client.wait_for_host(args.wait):
            seen = visible_hosts(session)
            raise SystemExit(f"nav2-pyif-bench host: no planner host on {args.key}; {seen}")
        progress(f"configuring a session on {args.key}")
        client.configure()
        client.activate()
        xs = np.linspace(0.0, 5.0, 101)
        client.set_plan(Plan(np.column_stack([xs, np.zeros_like(xs)]), frame_id="odom"))
        period = 1.0 / args.rate if args.rate > 0 else 0.0
        samples: list[int] = []
        next_at = time.monotonic()
        progress(f"{args.calls} calls at {args.rate:g} Hz" if period else f"{args.calls} calls")
        for i in range(args.calls):
            if period:
                next_at += period
                time.sleep(max(0.0, next_at - time.monotonic()))
            pose = _pose(0.2 * math.sin(i / 50.0), 0.0)
            start = time.perf_counter_ns()
            client.compute_velocity_commands(pose, Twist())
            samples.append(time.perf_counter_ns() - start)
        client.deactivate()
        client.cleanup()
    finally:
        client.close()
        session.close()
    summary = Summary.of_ns(samples)
    return {"key": args.key, "host": client.last_host, "rate_hz": args.rate, **vars(summary)}


def report(results: dict[str, Any]) -> str:
    rate = f"{results['rate_hz']:g} Hz" if results["rate_hz"] > 0 else "back to back"
    summary = Summary(results["n"], results["median_us"], results["p99_us"], results["mean_us"])
    return "\n".join(
        [
            f"control cycle against host {results['host']} on {results['key']} ({rate}):",
            header_row(),
            summary.row("compute_velocity_commands round trip"),
        ]
    )
