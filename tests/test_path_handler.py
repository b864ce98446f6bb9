"""A Python path handler (Nav2 Lyrical's nav2_core::PathHandler) served by a real planner host
over real Zenoh sessions on loopback: the plan pruned as Nav2's FeasiblePathHandler prunes it,
its call carried by the checks' query in Lyrical's control cycle (no extra query per cycle),
a bad answer an InvalidPath, a killed host NoValidControl and a restarted one given the plan
again."""

from __future__ import annotations

from typing import Any

import msgpack
import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif import InvalidPath, NoValidControl, Plan
from nav2_pyif.client import (
    ControlCycle,
    ControllerClient,
    GoalCheckerClient,
    PathHandlerClient,
    ProgressCheckerClient,
)
from nav2_pyif_protocol.keys import KeySpace

from tests.conftest import make_costmap
from tests.test_control_cycle import serving_the_cycle
from tests.test_smoother_and_checker_hosts import GENEROUS, no_costmap, pose, stamped

pytestmark = pytest.mark.integration

CONTROLLER = "nav2_pyif/test_robot/follow_path"
GOAL = "nav2_pyif/test_robot/goal_checker"
PROGRESS = "nav2_pyif/test_robot/progress_checker"
HANDLER = "nav2_pyif/test_robot/path_handler"
KEYS = (CONTROLLER, GOAL, PROGRESS, HANDLER)
PRUNING = "nav2_pyif_planners.path_handler:PruningPathHandler"
# a straight plan along y = 0.5, a pose every 5 cm from x = 0 to 3 m (Nav2's planners' spacing)
PLAN = Plan(np.column_stack([np.linspace(0.0, 3.0, 61), np.full(61, 0.5)]), "odom")


def serve_all(start_host: Any, handler: str = PRUNING) -> Any:
    """One host serving the four plugins of Lyrical's controller_server."""
    return start_host(
        *serving_the_cycle(CONTROLLER, GOAL, PROGRESS), "--serve", f"{HANDLER}={handler}"
    )


def connect(cls: Any, zsession_factory: Any, host: Any, key: str, **kw: Any) -> Any:
    made = cls(zsession_factory(host.endpoint), key, timeouts=GENEROUS, **kw)
    assert made.wait_for_host(15), host.log()
    made.configure()
    return made


def cycle_on(zsession_factory: Any, host: Any, handler: bool) -> ControlCycle:
    controller = connect(
        ControllerClient, zsession_factory, host, CONTROLLER, costmap=make_costmap()
    )
    controller.activate()
    path_handler = None
    if handler:
        params = {"prune_distance": 1.02}  # off the 5 cm grid: no rounding at the edge
        path_handler = connect(
            PathHandlerClient,
            zsession_factory,
            host,
            HANDLER,
            costmap=make_costmap(),
            params=params,
        )
    return ControlCycle(
        controller,
        connect(GoalCheckerClient, zsession_factory, host, GOAL, costmap=make_costmap()),
        connect(ProgressCheckerClient, zsession_factory, host, PROGRESS, costmap=no_costmap()),
        path_handler,
    )


def queries(session: Any) -> int:
    """The queries the host answered on the four keys (what `nav2-pyif hosts` shows)."""
    total = 0
    for key in KEYS:
        for reply in session.get(KeySpace(key).admin_info, timeout=5.0):
            if reply.ok is not None:
                total += msgpack.unpackb(reply.ok.payload.to_bytes()).get("queries", 0)
    return total


def lyrical_cycle(cycle: ControlCycle, robot: Any, goal: Any) -> tuple[int, int] | None:
    """One cycle in Lyrical controller_server's order: the goal check, the progress check, the
    path handler's segment (the C++ handler's, a fixed 1 m window, when no Python one) and the
    command with that part of the plan. The segment, or None when the goal is reached."""
    if cycle.is_goal_reached(robot, goal, Twist()):
        return None
    assert cycle.check(robot)
    if cycle.path_handler is not None:
        start, end = cycle.find_plan_segment(robot)
    else:
        start = int(np.argmin(np.abs(PLAN.array[:, 0] - robot.pose.position.x)))
        end = min(start + 21, len(PLAN))
    cycle.controller.follow(Plan(PLAN.array[start:end], "odom"), stamped(3.0, 0.5, 0.0))
    cmd = cycle.compute_velocity_commands(robot, Twist())
    assert cmd.twist.linear.x == end - start  # EchoController: the plan's length it got
    return start, end


def test_the_plan_is_pruned_and_the_segment_rides_with_the_checks(
    start_host: Any, zsession_factory: Any
) -> None:
    host = serve_all(start_host)
    session = zsession_factory(host.endpoint)
    goal = pose(3.0, 0.5)
    spent = {}
    for handler in (False, True):  # Lyrical's cycle with Nav2's own path handler, then Python's
        cycle = cycle_on(zsession_factory, host, handler)
        if cycle.path_handler is not None:
            cycle.path_handler.set_plan(PLAN)
        before, segments = queries(session), []
        for step in range(12):
            segment = lyrical_cycle(cycle, stamped(0.2 * step, 0.5, 100.0 + step), goal)
            assert segment is not None  # the goal is not reached before 3 m
            segments.append(segment)
        spent[handler] = queries(session) - before
        assert spent[handler] == cycle.queries
    # no extra round trip: the goal check's query carries the check and the segment, the
    # command goes on its own (it needs the segment's plan): two queries a cycle either way
    assert spent == {False: 24, True: 24}, spent
    assert cycle.carried_used == 24  # each cycle's check and segment came with the goal check
    # pruned as Nav2's FeasiblePathHandler: from the pose closest to the robot, 1 m of plan on
    starts = [s for s, _ in segments]
    assert starts == [4 * step for step in range(12)]
    assert all(end - start == 21 for start, end in segments[:11])  # 1 m: 20 steps of 5 cm
    assert segments[-1] == (44, 61)  # cut at the plan's end


def test_a_bad_segment_is_invalid_path_and_the_next_call_works(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", HANDLER, "--planner", "path_handlers:ByPose")
    handler = connect(PathHandlerClient, zsession_factory, host, HANDLER, costmap=make_costmap())
    handler.set_plan(PLAN)
    assert handler.find_plan_segment(stamped(3.0, 9.0, 1.0)) == (3, 9)
    for start, end in ((5, 5), (9, 3), (0, 62)):
        with pytest.raises(InvalidPath, match=rf"returned \({start}, {end}\).*61 poses"):
            handler.find_plan_segment(stamped(start, end, 2.0))
    assert handler.find_plan_segment(stamped(0.0, 61.0, 3.0)) == (0, 61)


def test_a_killed_host_is_no_valid_control_and_a_new_one_gets_the_plan_again(
    start_host: Any, zsession_factory: Any
) -> None:
    """As for the controller: a host failure is NoValidControl (controller_server holds the
    robot and retries within its failure_tolerance); the restarted host's new session is
    given the plan before the segment is asked."""
    host = start_host("--key", HANDLER, "--planner", PRUNING)
    handler = connect(PathHandlerClient, zsession_factory, host, HANDLER, costmap=make_costmap())
    handler.set_plan(PLAN)
    assert handler.find_plan_segment(stamped(1.0, 0.5, 1.0))[0] == 20
    host.kill()
    assert handler.hosts.wait_for(lambda alive: not alive, 10)
    with pytest.raises(NoValidControl):
        handler.find_plan_segment(stamped(1.1, 0.5, 2.0))
    start_host("--key", HANDLER, "--planner", PRUNING, port=host.port)
    assert handler.wait_for_host(15)
    assert handler.find_plan_segment(stamped(1.5, 0.5, 3.0))[0] == 30
    assert handler.resyncs == 1
