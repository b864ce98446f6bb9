"""planner-host --watch: how long from saving a planner's source file to the first reply of
the new version. A real host watches a module file; the benchmark writes version N of it
(a controller that answers linear.x = N) and calls compute_velocity_commands at 200 Hz, as
a controller_server would at its fastest, until the reply says N. Each isolation mode: a
process (a fresh worker imports the new version and takes the live session) and none (the
module re-imported in the host).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path
from typing import Any

from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.common.option_types import positive_int

from nav2_pyif_bench.protocol_bench import costmap, open_session, progress

KEY = "bench/watch/FollowPath"
MODULE = "watched_bench_ctl"
TARGET_MS = 1000.0
POLL_S = 0.005  # 200 Hz
SOURCE = """
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller


class Watched(Controller):
    def compute_velocity_commands(self, pose, velocity, goal_checker):
        cmd = TwistStamped()
        cmd.twist.linear.x = {version}.0
        return cmd
"""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--edits", type=positive_int, default=20, help="edits per isolation mode, >= 1 (default 20)"
    )
    p.add_argument("--quick", action="store_true", help="5 edits per isolation mode")


def run(args: argparse.Namespace) -> dict[str, Any]:
    edits = 5 if args.quick else args.edits
    return {mode: _measure(mode, edits) for mode in ("process", "none")}


def _measure(isolation: str, edits: int) -> dict[str, Any]:
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_watch_bench_") as folder:
        source = Path(folder) / f"{MODULE}.py"
        source.write_text(SOURCE.format(version=0))
        args = ["--watch", "--isolation", isolation, "--path", folder]
        planner = {"key": KEY, "planner": f"{MODULE}:Watched"}
        with PlannerHostProcess([planner], args=args, log_level="INFO") as host:
            session = open_session([host.endpoint])
            try:
                client = ControllerClient(
                    session, KEY, costmap(20), timeouts=Timeouts(call=2.0, configure=30.0)
                )
                assert client.wait_for_host(30), f"no planner host on {KEY}: {host.log()}"
                client.configure()
                client.activate()
                _wait_watching(host)
                progress(f"{edits} edits, isolation {isolation}")
                samples = [_edit_to_served(client, source, n) for n in range(1, edits + 1)]
            finally:
                session.close()
    samples.sort()
    return {
        "edits": edits,
        "median_ms": samples[len(samples) // 2],
        "p99_ms": samples[min(len(samples) - 1, round(0.99 * (len(samples) - 1)))],
        "max_ms": samples[-1],
    }


def _wait_watching(host: PlannerHostProcess) -> None:
    deadline = time.monotonic() + 30
    while "--watch: " not in host.log():
        assert time.monotonic() < deadline, f"the host never said it watches: {host.log()}"
        time.sleep(0.05)


def _edit_to_served(client: ControllerClient, source: Path, version: int) -> float:
    """Milliseconds from writing ``version`` to its first reply."""
    pose = PoseStamped()
    pose.header.frame_id = "odom"
    pose.pose.orientation.w = 1.0
    time.sleep(0.3)  # an edit some time after the last reload, as a person types
    saved = time.perf_counter()
    source.write_text(SOURCE.format(version=version))
    deadline = saved + 30
    while client.compute_velocity_commands(pose, Twist()).twist.linear.x != version:
        assert time.perf_counter() < deadline, f"version {version} not served within 30 s"
        time.sleep(POLL_S)
    return (time.perf_counter() - saved) * 1000.0


def report(results: dict[str, Any]) -> str:
    lines = [
        "planner-host --watch: edit saved -> first reply of the new version",
        f"  {'isolation':<12} {'median ms':>10} {'p99 ms':>10} {'max ms':>10} {'edits':>6}",
    ]
    for mode, r in results.items():
        lines.append(
            f"  {mode:<12} {r['median_ms']:>10.0f} {r['p99_ms']:>10.0f} {r['max_ms']:>10.0f} "
            f"{r['edits']:>6d}"
        )
    for mode, r in results.items():
        lines.append(
            f"  {mode}: p99 {r['p99_ms']:.0f} ms (target < {TARGET_MS:.0f} ms): "
            f"{'MET' if r['p99_ms'] < TARGET_MS else 'NOT MET'}"
        )
    return "\n".join(lines)
