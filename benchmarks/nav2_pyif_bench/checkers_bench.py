"""The control cycle with Python goal and progress checkers (PROTOCOL.md section 15),
side by side in one run against one planner host (worker processes, the default):

- controller only: compute_velocity_commands, one query;
- checkers, a query each: is_goal_reached, check, compute_velocity_commands (Nav2's order);
- checkers carried: the goal check carries the other two (``ControlCycle``), one query.

The rounds interleave the three (round-robin, ``--calls`` cycles each), so load on the
machine hits them alike. The controller is the benchmarks' trivial one; the checkers are the
reference StoppedGoalChecker and SimpleProgressChecker.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import numpy as np
from geometry_msgs.msg import Pose, PoseStamped, Twist
from nav2_pyif import Costmap, Plan
from nav2_pyif._messages import ns_to_stamp
from nav2_pyif.client import (
    ControlCycle,
    ControllerClient,
    GoalCheckerClient,
    ProgressCheckerClient,
    Timeouts,
)
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.common.option_types import positive_int

from nav2_pyif_bench.protocol_bench import costmap, open_session, progress
from nav2_pyif_bench.stats import Summary, header_row

CONTROLLER = "bench/robot/FollowPath"
GOAL = "bench/robot/goal_checker"
PROGRESS = "bench/robot/progress_checker"
CHECKERS = "nav2_pyif_planners.checker_plugins"
TIMEOUTS = Timeouts(call=2.0, lifecycle=5.0, configure=30.0)
ROWS = ("controller only (1 query)", "checkers, a query each (3)", "checkers carried (1 query)")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--calls", type=positive_int, default=3000, help="cycles per variant, >= 1 (default 3000)"
    )
    p.add_argument("--quick", action="store_true", help="300 cycles per variant")


def moving_robot(i: int) -> Any:
    """The robot's pose at cycle ``i``: moving along x at 0.2 m/s, stamped at 20 Hz."""
    msg = PoseStamped()
    msg.header.frame_id = "odom"
    msg.header.stamp = ns_to_stamp(1_000_000_000 * 100 + i * 50_000_000)  # 20 Hz
    msg.pose.position.x = 0.01 * i  # 0.2 m/s: never at the goal, always progressing
    msg.pose.orientation.w = 1.0
    return msg


def run(args: argparse.Namespace) -> dict[str, Any]:
    calls = 300 if args.quick else args.calls
    entries = [
        {"key": CONTROLLER, "planner": "nav2_pyif_bench.planners:TrivialController"},
        {"key": GOAL, "planner": f"{CHECKERS}:StoppedGoalChecker"},
        {"key": PROGRESS, "planner": f"{CHECKERS}:SimpleProgressChecker"},
    ]
    with PlannerHostProcess(entries) as host:
        session = open_session([host.endpoint])
        try:
            return _measure(session, calls)
        finally:
            session.close()


def _measure(session: Any, calls: int) -> dict[str, Any]:
    empty = Costmap(np.zeros((0, 0), np.uint8), 1.0, frame_id="odom")
    controller = ControllerClient(session, CONTROLLER, costmap(200), timeouts=TIMEOUTS)
    goal = GoalCheckerClient(session, GOAL, costmap(200), timeouts=TIMEOUTS)
    prog = ProgressCheckerClient(session, PROGRESS, empty, timeouts=TIMEOUTS)
    for client in (controller, goal, prog):
        assert client.wait_for_host(30), f"no planner host on {client.keys.prefix}"
        client.configure()
    controller.activate()
    controller.set_plan(Plan(np.column_stack([np.linspace(0, 50, 500), np.zeros(500)]), "odom"))
    cycle = ControlCycle(controller, goal, prog)
    tolerances = goal.get_tolerances()
    target, still = Pose(), Twist()
    target.position.x, target.orientation.w = 100.0, 1.0

    def alone(robot: Any) -> None:
        controller.compute_velocity_commands(robot, still, tolerances)

    def separate(robot: Any) -> None:
        if not goal.is_goal_reached(robot.pose, target, still) and prog.check(robot):
            controller.compute_velocity_commands(robot, still, tolerances)

    def carried(robot: Any) -> None:
        if not cycle.is_goal_reached(robot, target, still, tolerances) and cycle.check(robot):
            cycle.compute_velocity_commands(robot, still, tolerances)

    variants = (alone, separate, carried)
    samples: list[list[int]] = [[] for _ in variants]
    progress(f"{calls} cycles of each variant, interleaved")
    for i in range(calls + 50):
        robot = moving_robot(i)
        for variant, out in zip(variants, samples, strict=True):
            start = time.perf_counter_ns()
            variant(robot)
            if i >= 50:  # warm-up
                out.append(time.perf_counter_ns() - start)
    summaries = {row: Summary.of_ns(s) for row, s in zip(ROWS, samples, strict=True)}
    return {
        "calls": calls,
        "carried_used": cycle.carried_used,
        "sent_alone": cycle.sent_alone,
        "rows": {row: vars(s) for row, s in summaries.items()},
    }


def report(results: dict[str, Any]) -> str:
    rows = {row: Summary(**v) for row, v in results["rows"].items()}
    lines = ["control cycle with Python goal + progress checkers, one host", header_row(44)]
    lines += [summary.row(row, 44) for row, summary in rows.items()]
    base = rows[ROWS[0]].median_us
    for row in ROWS[1:]:
        lines.append(f"  {row}: +{rows[row].median_us - base:.1f} µs median over the controller")
    lines.append(
        f"  carried cycles: {results['carried_used']} calls answered from carried replies, "
        f"{results['sent_alone']} sent alone"
    )
    return "\n".join(lines)
