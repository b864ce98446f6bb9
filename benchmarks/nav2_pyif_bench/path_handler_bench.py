"""Lyrical's control cycle with a Python path handler (PROTOCOL.md section 19), side by side in
one run against one planner host (worker processes, the default). Every variant has the
Python goal checker, progress checker and controller; the cycle is Lyrical's: the goal check,
the progress check, the path handler's segment, then the command with that part of the plan.

- Nav2's own path handler: the segment computed in this process (the reference rule), the
  goal check carrying the progress check;
- Python path handler, a query each: the segment asked on its own query;
- Python path handler, carried: the goal check's query carries the check and the segment.

The rounds interleave the three (round-robin, ``--calls`` cycles each), so load on the machine
hits them alike; each row also says how many queries a cycle took.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from geometry_msgs.msg import Pose, Twist
from nav2_pyif import Costmap, Plan
from nav2_pyif.client import (
    ControlCycle,
    ControllerClient,
    GoalCheckerClient,
    PathHandlerClient,
    ProgressCheckerClient,
)
from nav2_pyif.common.host_process import PlannerHostProcess

from nav2_pyif_bench.checkers_bench import CHECKERS, TIMEOUTS, add_arguments, moving_robot
from nav2_pyif_bench.protocol_bench import costmap, open_session, progress
from nav2_pyif_bench.stats import Summary, header_row

__all__ = ["add_arguments", "report", "run"]

KEYS = ("follow_path", "goal_checker", "progress_checker", "path_handler")
ROWS = (
    "Nav2's path handler (in process)",
    "Python path handler, a query each",
    "Python path handler, carried",
)
# the plan: 50 m along x, a pose every 5 cm (Nav2's planners' spacing)
PLAN = Plan(np.column_stack([np.linspace(0.0, 50.0, 1001), np.zeros(1001)]), "odom")
PRUNE = 40  # poses of the segment Nav2's own handler gives (2 m)


def run(args: argparse.Namespace) -> dict[str, Any]:
    calls = 300 if args.quick else args.calls
    planners = (
        "nav2_pyif_bench.planners:TrivialController",
        f"{CHECKERS}:StoppedGoalChecker",
        f"{CHECKERS}:SimpleProgressChecker",
        "nav2_pyif_planners.path_handler:PruningPathHandler",
    )
    entries = [
        {"key": f"bench/robot/{key}", "planner": planner}
        for key, planner in zip(KEYS, planners, strict=True)
    ]
    with PlannerHostProcess(entries) as host:
        session = open_session([host.endpoint])
        try:
            return _measure(session, calls)
        finally:
            session.close()


def _cycle(session: Any, handler: bool) -> ControlCycle:
    """A controller_server's Python plugins (sessions of their own on the host), with a
    Python path handler when ``handler``; each client records the queries it sends."""
    empty = Costmap(np.zeros((0, 0), np.uint8), 1.0, frame_id="odom")
    key = [f"bench/robot/{k}" for k in KEYS]
    kw: dict[str, Any] = {"timeouts": TIMEOUTS, "record_calls": True}
    controller = ControllerClient(session, key[0], costmap(200), **kw)
    goal = GoalCheckerClient(session, key[1], costmap(200), **kw)
    prog = ProgressCheckerClient(session, key[2], empty, **kw)
    clients: list[Any] = [controller, goal, prog]
    path_handler = None
    if handler:
        path_handler = PathHandlerClient(session, key[3], costmap(200), **kw)
        clients.append(path_handler)
    for client in clients:
        assert client.wait_for_host(30), f"no planner host on {client.keys.prefix}"
        client.configure()
    controller.activate()
    if path_handler is not None:
        path_handler.set_plan(PLAN)
    return ControlCycle(controller, goal, prog, path_handler)


def _measure(session: Any, calls: int) -> dict[str, Any]:
    cycles = [_cycle(session, handler) for handler in (False, True, True)]
    target, still = Pose(), Twist()
    target.position.x, target.orientation.w = 100.0, 1.0
    goal = moving_robot(0)
    goal.pose.position.x = PLAN.array[-1, 0]

    def lyrical(cycle: ControlCycle, segment: Callable[[Any], tuple[int, int]]) -> Any:
        def one(robot: Any) -> None:
            if cycle.is_goal_reached(robot, target, still) or not cycle.check(robot):
                return
            start, end = segment(robot)
            cycle.controller.follow(Plan(PLAN.array[start:end], "odom"), goal)
            cycle.compute_velocity_commands(robot, still)

        return one

    def nav2s(robot: Any) -> tuple[int, int]:
        here = round(robot.pose.position.x / 0.05)
        return here, min(here + PRUNE, len(PLAN))

    def alone(robot: Any) -> tuple[int, int]:
        handler = cycles[1].path_handler
        assert handler is not None
        return handler.find_plan_segment(robot)

    variants = (
        lyrical(cycles[0], nav2s),
        lyrical(cycles[1], alone),
        lyrical(cycles[2], cycles[2].find_plan_segment),
    )
    samples: list[list[int]] = [[] for _ in variants]
    progress(f"{calls} Lyrical cycles of each variant, interleaved")
    for i in range(calls + 50):
        robot = moving_robot(i)
        if i == 50:  # warm-up done
            before = [_queries(cycle) for cycle in cycles]
        for variant, out in zip(variants, samples, strict=True):
            start = time.perf_counter_ns()
            variant(robot)
            if i >= 50:
                out.append(time.perf_counter_ns() - start)
    queries = [_queries(cycle) - sent for cycle, sent in zip(cycles, before, strict=True)]
    summaries = {row: Summary.of_ns(s) for row, s in zip(ROWS, samples, strict=True)}
    return {
        "calls": calls,
        "queries_per_cycle": {row: q / calls for row, q in zip(ROWS, queries, strict=True)},
        "rows": {row: vars(s) for row, s in summaries.items()},
    }


def _queries(cycle: ControlCycle) -> int:
    """The queries the cycle's clients sent (carried requests travel inside them)."""
    clients = (cycle.controller, cycle.goal_checker, cycle.progress_checker, cycle.path_handler)
    return sum(len(c.records or []) for c in clients if c is not None)


def report(results: dict[str, Any]) -> str:
    rows = {row: Summary(**v) for row, v in results["rows"].items()}
    per_cycle = results["queries_per_cycle"]
    lines = [
        "Lyrical's control cycle, Python goal + progress checkers + controller, one host",
        header_row(44) + f" {'queries/cycle':>14}",
    ]
    lines += [f"{s.row(row, 44)} {per_cycle[row]:>14.2f}" for row, s in rows.items()]
    base = rows[ROWS[0]].median_us
    for row in ROWS[1:]:
        lines.append(f"  {row}: +{rows[row].median_us - base:.1f} µs median over Nav2's own")
    return "\n".join(lines)
