"""Python behaviours (behavior_server's plugins) served by a real planner host over real Zenoh
sessions on loopback, driven as TimedBehavior drives them: on_run, on_cycle_update at the
cycle rate with the robot moved by each command, on_action_completion. Errors, a crashed
worker and a hot swap in the middle of an action."""

from __future__ import annotations

import math
import os
import signal
import time
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from nav2_pyif import Costmap, Failure, Status, Step
from nav2_pyif.client import BehaviorClient
from nav2_pyif.runner.run import pose_msg
from nav2_pyif.tools.admin import request_reload

from tests.conftest import wait_until
from tests.test_smoother_and_checker_hosts import GENEROUS, worker_pid

pytestmark = pytest.mark.integration

KEY = "nav2_pyif/test_robot/backup"
BACKUP = "nav2_msgs/action/BackUp"
FOOTPRINT = [[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]


def room(wall_behind: bool) -> Costmap:
    """A 4 m x 4 m local costmap (5 cm), walls around; the robot will be at (2, 2) facing +x;
    ``wall_behind``: a wall 0.35 m behind it, across the whole room."""
    grid = np.zeros((80, 80), np.uint8)
    grid[:2, :] = grid[-2:, :] = grid[:, :2] = grid[:, -2:] = Costmap.LETHAL
    if wall_behind:
        grid[:, 32:34] = Costmap.LETHAL  # x 1.60 .. 1.70 m
    return Costmap(grid, 0.05, frame_id="odom", version=1, footprint=FOOTPRINT)


def connect(
    start_host: Any, zsession_factory: Any, planner: str, costmap: Costmap, *extra: str
) -> tuple[Any, BehaviorClient]:
    host = start_host("--key", KEY, "--planner", planner, *extra)
    client = BehaviorClient(zsession_factory(host.endpoint), KEY, costmap, timeouts=GENEROUS)
    assert client.wait_for_host(15), host.log()
    client.configure()
    client.activate()
    return host, client


def cycle(
    client: BehaviorClient, x: float, y: float, yaw: float, dt: float = 0.1, limit: int = 300,
    between: Any = None,
) -> tuple[Step, list[tuple[float, float, float]]]:  # fmt: skip
    """Cycle as TimedBehavior does until the step is not RUNNING, moving the robot by each
    command for ``dt``; returns the last step and the poses visited."""
    visited = [(x, y, yaw)]
    for i in range(limit):
        if between is not None:
            between(i)
        step = client.cycle_update(pose_msg(x, y, yaw, "odom"), i * dt)
        if step.status is not Status.RUNNING:
            return step, visited
        twist = step.cmd_vel.twist
        yaw += twist.angular.z * dt
        x += twist.linear.x * dt * math.cos(yaw)
        y += twist.linear.x * dt * math.sin(yaw)
        visited.append((x, y, yaw))
    raise AssertionError(f"still running after {limit} cycles")


BACKUP_30 = {"target_x": -0.3, "target_y": 0.0, "target_z": 0.0, "speed": 0.15,
             "time_allowance": 10.0, "disable_collision_checks": False}  # fmt: skip


def test_freest_backup_backs_straight_when_there_is_room(
    start_host: Any, zsession_factory: Any
) -> None:
    costmap = room(wall_behind=False)
    _, client = connect(
        start_host, zsession_factory, "nav2_pyif_planners.free_backup:FreestBackUp", costmap
    )
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom")) == (
        Status.SUCCEEDED,
        Failure.NONE,
    )
    step, visited = cycle(client, 2.0, 2.0, 0.0)
    assert step.status is Status.SUCCEEDED and step.failure is Failure.NONE
    x, y, yaw = visited[-1]
    assert x < 2.0 - 0.3 + 1e-9 and abs(y - 2.0) < 1e-9 and yaw == 0.0  # straight back
    assert float(step.feedback["distance_traveled"]) >= 0.3  # type: ignore[arg-type]
    client.action_completion("succeeded", 2.1)


def test_freest_backup_turns_away_from_a_wall_behind_and_never_touches_it(
    start_host: Any, zsession_factory: Any
) -> None:
    """Nav2's BackUp would fail with COLLISION_AHEAD here; this one turns in place towards
    the freest heading and drives 0.3 m there, every pose of the way collision-free."""
    costmap = room(wall_behind=True)
    _, client = connect(
        start_host, zsession_factory, "nav2_pyif_planners.free_backup:FreestBackUp", costmap
    )
    status, _ = client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))
    assert status is Status.SUCCEEDED
    step, visited = cycle(client, 2.0, 2.0, 0.0)
    assert step.status is Status.SUCCEEDED, step
    poses = np.array(visited)
    assert (costmap.footprint_costs(poses) < Costmap.LETHAL).all()
    assert poses[:, 0].min() > 1.70  # never crossed the wall
    start, end = poses[0, :2], poses[-1, :2]
    assert np.hypot(*(end - start)) >= 0.3 - 1e-6
    assert abs(poses[-1, 2]) > 0.3  # it turned


def test_freest_backup_fails_with_collision_ahead_when_boxed_in(
    start_host: Any, zsession_factory: Any
) -> None:
    grid = np.full((80, 80), Costmap.LETHAL, np.uint8)
    grid[36:44, 34:46] = 0  # a 0.6 x 0.4 m pocket around the robot
    costmap = Costmap(grid, 0.05, frame_id="odom", version=1, footprint=FOOTPRINT)
    _, client = connect(
        start_host, zsession_factory, "nav2_pyif_planners.free_backup:FreestBackUp", costmap
    )
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom")) == (
        Status.FAILED,
        Failure.COLLISION_AHEAD,
    )


def test_a_costmap_change_reaches_the_behaviour_between_cycles(
    start_host: Any, zsession_factory: Any
) -> None:
    """An obstacle appearing behind the robot while it backs up: the next cycle's check sees
    the new costmap (sent because its version changed) and stops with COLLISION_AHEAD."""
    _, client = connect(
        start_host,
        zsession_factory,
        "nav2_pyif_planners.free_backup:FreestBackUp",
        room(wall_behind=False),
    )
    long_backup = dict(BACKUP_30, target_x=-1.0)
    assert client.run(BACKUP, long_backup, pose_msg(2.0, 2.0, 0.0, "odom"))[0] is Status.SUCCEEDED

    def obstacle(i: int) -> None:
        if i == 3:
            blocked = room(wall_behind=True).data.copy()
            client.update_costmap(room(False).with_costs(blocked, version=2))

    step, visited = cycle(client, 2.0, 2.0, 0.0, between=obstacle)
    assert (step.status, step.failure) == (Status.FAILED, Failure.COLLISION_AHEAD)
    assert len(visited) == 4 and step.cmd_vel is None


def test_a_raising_behaviour_fails_its_cycle_with_the_traceback_and_the_next_call_works(
    start_host: Any, zsession_factory: Any
) -> None:
    host, client = connect(start_host, zsession_factory, "behaviors:Creep", room(False))
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))[0] is Status.SUCCEEDED
    client.set_parameters({"fault": "raise"})
    with pytest.raises(api.ControllerException, match=r"KeyError.*no such key"):
        client.cycle_update(pose_msg(2.0, 2.0, 0.0, "odom"), 0.1)
    assert "behaviors.py" in host.log() and "on_cycle_update failed" in host.log()
    client.set_parameters({"fault": "nan"})
    with pytest.raises(api.ControllerException, match=r"non-finite velocity: linear\.x=nan"):
        client.cycle_update(pose_msg(2.0, 2.0, 0.0, "odom"), 0.2)
    client.set_parameters({"fault": "running_at_run"})
    with pytest.raises(api.ControllerException, match="on_run returned RUNNING"):
        client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))
    client.set_parameters({"fault": ""})
    assert client.run(BACKUP, dict(BACKUP_30, speed=0.0), pose_msg(2.0, 2.0, 0.0, "odom")) == (
        Status.FAILED,
        Failure.INVALID_INPUT,
    )
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))[0] is Status.SUCCEEDED
    assert cycle(client, 2.0, 2.0, 0.0)[0].status is Status.SUCCEEDED


def test_a_worker_killed_mid_action_goes_on_with_the_action(
    start_host: Any, zsession_factory: Any
) -> None:
    """SIGKILL of the behaviour's worker halfway: the host replays configure, activate and
    the action's on_run on a new worker, so the next cycle continues from the start pose
    (the plugin sees no SessionUnknown)."""
    host, client = connect(start_host, zsession_factory, "behaviors:Creep", room(False))
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))[0] is Status.SUCCEEDED

    def kill(i: int) -> None:
        if i == 5:
            first = worker_pid(host, KEY)
            assert first is not None
            os.kill(first, signal.SIGKILL)
            assert wait_until(lambda: worker_pid(host, KEY) not in (first, None), 30)
            time.sleep(0.2)

    step, visited = cycle(client, 2.0, 2.0, 0.0, between=kill)
    assert step.status is Status.SUCCEEDED
    assert abs(visited[-1][0] - (2.0 - 0.3)) < 0.02  # 0.3 m from where the action started
    assert step.feedback["runs"] == 1  # the replayed on_run; no second run from the client
    assert client.resyncs == 0
    assert "restarted, 1 session(s) restored" in host.log()


def test_hot_swap_mid_action_carries_the_action_to_the_new_behaviour(
    start_host: Any, zsession_factory: Any
) -> None:
    _, client = connect(
        start_host, zsession_factory, "behaviors:Creep", room(False),
        "--allow-remote-reload", "--reload-allow", "behaviors:*",
    )  # fmt: skip
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))[0] is Status.SUCCEEDED
    first = client.cycle_update(pose_msg(2.0, 2.0, 0.0, "odom"), 0.0)
    assert first.cmd_vel.twist.linear.x == pytest.approx(-0.15)
    message = request_reload(client.session, KEY, planner="behaviors:CreepFaster")
    assert "1 session(s) carried over" in message
    swapped = client.cycle_update(pose_msg(1.99, 2.0, 0.0, "odom"), 0.1)
    assert swapped.status is Status.RUNNING
    assert swapped.cmd_vel.twist.linear.x == pytest.approx(-0.30)
    assert swapped.feedback["distance_traveled"] == pytest.approx(0.01)  # the same start pose
    assert client.resyncs == 0


def test_a_restarted_host_is_given_the_running_action_again(
    start_host: Any, zsession_factory: Any
) -> None:
    """The host itself restarted (a new process on the same port): the client re-sends
    configure, activate and the action's on_run (as the C++ plugin does), then the cycle."""
    host, client = connect(start_host, zsession_factory, "behaviors:Creep", room(False))
    assert client.run(BACKUP, BACKUP_30, pose_msg(2.0, 2.0, 0.0, "odom"))[0] is Status.SUCCEEDED
    host.kill()
    assert client.hosts.wait_for(lambda alive: not alive, 10)
    start_host("--key", KEY, "--planner", "behaviors:Creep", port=host.port)
    assert client.wait_for_host(15)
    step = client.cycle_update(pose_msg(1.9, 2.0, 0.0, "odom"), 0.7)
    assert step.status is Status.RUNNING
    assert step.feedback["distance_traveled"] == pytest.approx(0.1)
    assert client.resyncs == 1
