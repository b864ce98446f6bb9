"""One planner for a fleet (planner-host --batch): the control cycles of several robots in one
batched call, through a real host, real worker processes and the reference client over
Zenoh on loopback. Each robot gets its own result and its own typed error; a crash or a hang
fails only the cycle of the robots in that batch, and every session is restored."""

from __future__ import annotations

import re
import statistics
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif import Plan
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.tools.admin import request_reload

from tests.conftest import (
    free_port,
    host_process,
    make_costmap,
    nav2_pyif_tool,
    open_client_session,
    wait_until,
)
from tests.test_host_e2e import pose

pytestmark = pytest.mark.integration

ROBOTS = 3
SPEEDS = [0.1, 0.2, 0.3]  # each robot's own parameter: mixed in one batch
PLAN_LENGTHS = [10, 20, 30]
WINDOW_MS = 40.0  # long, so that the robots of a round surely share a batch
PERIOD = 0.2  # [s] the control period it is bounded by (1/4 of it at most)
TIMEOUTS = Timeouts(call=3.0, lifecycle=5.0, configure=20.0)


def key(i: int) -> str:
    return f"nav2_pyif/fleet{i}/FollowPath"


class Fleet:
    """A host serving ROBOTS batched keys (and ``extra`` other --serve flags), a configured
    client per robot, each with its own speed and plan."""

    def __init__(self, tmp: Path, planner: str = "batch_planners:BatchEcho", *extra: str):
        serves = [f"--serve={key(i)}={planner}" for i in range(ROBOTS)]
        self.host: PlannerHostProcess = host_process(
            free_port(),
            [
                *serves,
                *extra,
                "--batch",
                "--batch-window",
                str(WINDOW_MS),
                "--control-period",
                str(PERIOD),
                "--deadline",
                "0.5",
                "--hang-grace",
                "1.0",
                "--allow-remote-reload",
                "--reload-allow",
                "batch_planners:*",
            ],
            tmp / "host.log",
        ).start()
        self.session = open_client_session(self.host.endpoint)
        self.clients: list[Any] = []
        try:
            self.clients += [self.robot(i) for i in range(ROBOTS)]
        except BaseException:  # no host left behind by a set-up that failed
            self.close()
            raise

    def robot(self, i: int, speed: float | None = None, plan: int | None = None) -> Any:
        client = ControllerClient(
            self.session,
            key(i),
            make_costmap(),
            params={"speed": SPEEDS[i] if speed is None else speed},
            timeouts=TIMEOUTS,
        )
        assert client.wait_for_host(30), self.host.log()
        client.configure()
        client.activate()
        length = PLAN_LENGTHS[i] if plan is None else plan
        client.set_plan(Plan(np.zeros((length, 3)), "odom"))
        return client

    def round(self, clients: list[Any] | None = None) -> list[Any]:
        """One control cycle of each robot, released together: a TwistStamped or the
        exception, per robot."""
        clients = self.clients if clients is None else clients
        results: list[Any] = [None] * len(clients)
        start = threading.Barrier(len(clients))

        def cycle(i: int) -> None:
            start.wait()
            try:
                results[i] = clients[i].compute_velocity_commands(pose(), Twist())
            except Exception as exc:
                results[i] = exc

        threads = [threading.Thread(target=cycle, args=(i,)) for i in range(len(clients))]
        for t in threads:
            t.start()
        for t in threads:
            t.join(30)
        return results

    def batched_round(self) -> list[Any]:
        """A round whose cycles shared one batched call (the first round after a pause
        is not batched: no robot waits for robots that have not called lately)."""
        for _ in range(20):
            results = self.round()
            if all(not isinstance(r, Exception) and r.twist.angular.z == ROBOTS for r in results):
                return results
        raise AssertionError(f"the robots' cycles never shared a batch: {results}")

    def set_fault(self, i: int, fault: str, **extra: Any) -> None:
        assert self.clients[i].set_parameters({"fault": fault, **extra}) == {}

    def clear_fault_once_back(self, i: int, timeout: float = 30.0) -> None:
        """The restarted worker got every session back, the fault parameter too: clear it
        the moment the worker answers again."""
        deadline = time.monotonic() + timeout
        while True:
            try:
                return self.set_fault(i, "none")
            except api.ControllerException:
                assert time.monotonic() < deadline, self.host.log()[-3000:]
                time.sleep(0.1)

    def assert_sessions_intact(self) -> None:
        """Each robot's own parameter and plan, in one batch, restored by the host (no
        client re-sent its state)."""
        for i, cmd in enumerate(self.batched_round()):
            assert (cmd.twist.linear.x, cmd.twist.linear.y) == (SPEEDS[i], PLAN_LENGTHS[i])
        assert all(client.resyncs == 0 for client in self.clients)

    def close(self) -> None:
        for client in self.clients:
            client.close()
        self.session.close()
        if self.host.proc is not None and self.host.proc.poll() is None:
            self.host.kill()


@pytest.fixture
def fleet(tmp_path: Path) -> Iterator[Fleet]:
    fleet = Fleet(tmp_path)
    yield fleet
    fleet.close()


def test_robots_with_their_own_parameters_share_one_batched_call(fleet: Fleet) -> None:
    fleet.assert_sessions_intact()  # speeds and plans of their own, wz: 3 robots per call
    log = fleet.host.log()
    assert f"batch group: batch_planners:BatchEcho serves {ROBOTS} key(s)" in log
    workers = {line for line in log.splitlines() if "FollowPath/** (controller, worker" in line}
    assert len({line.rsplit("worker ", 1)[1] for line in workers}) == 1, workers  # one worker


def test_a_lone_robot_does_not_wait_for_the_window(fleet: Fleet) -> None:
    lone = fleet.clients[0]
    lone.compute_velocity_commands(pose(), Twist())
    times, sizes = [], []
    for _ in range(20):
        started = time.perf_counter()
        cmd = lone.compute_velocity_commands(pose(), Twist())
        times.append(time.perf_counter() - started)
        sizes.append(cmd.twist.angular.z)
        time.sleep(0.02)
    assert set(sizes) == {1.0}
    # its batch leaves at once: nobody else called lately (the window is 40 ms)
    assert statistics.median(times) < WINDOW_MS / 1000 / 2, times


def test_a_robot_waits_at_most_the_window_for_one_that_stopped(fleet: Fleet) -> None:
    fleet.batched_round()  # every robot called lately: the next batch waits for them all
    started = time.perf_counter()
    cmd = fleet.clients[0].compute_velocity_commands(pose(), Twist())
    waited = time.perf_counter() - started
    assert cmd.twist.angular.z == 1.0  # the others never came: it left alone ...
    assert WINDOW_MS / 1000 * 0.9 < waited < WINDOW_MS / 1000 + 0.03, waited  # ... at the window
    time.sleep(2.5 * PERIOD)  # two periods without a call: they no longer count
    started = time.perf_counter()
    fleet.clients[0].compute_velocity_commands(pose(), Twist())
    assert time.perf_counter() - started < WINDOW_MS / 1000 / 2


def test_one_robots_nan_fails_that_robot_only(fleet: Fleet) -> None:
    fleet.batched_round()
    fleet.set_fault(1, "nan")
    results = fleet.round()
    assert isinstance(results[1], api.NoValidControl)
    assert "non-finite velocity: linear.x=nan" in str(results[1])
    for i in (0, 2):  # served in the same call as the NaN
        assert results[i].twist.linear.x == SPEEDS[i] and results[i].twist.angular.z == ROBOTS
    fleet.set_fault(1, "none")
    fleet.assert_sessions_intact()


def test_one_robots_own_error_is_typed_and_its_own(fleet: Fleet) -> None:
    fleet.batched_round()
    fleet.set_fault(2, "own_error")
    results = fleet.round()
    assert type(results[2]) is api.NoValidControl and "this robot's own error" in str(results[2])
    assert [r.twist.linear.x for r in results[:2]] == SPEEDS[:2]


def test_a_batched_call_that_raises_fails_its_robots_each_with_a_typed_error(
    fleet: Fleet,
) -> None:
    fleet.batched_round()
    fleet.set_fault(0, "raise")
    results = fleet.round()
    for result in results:
        assert isinstance(result, api.ControllerException), results
        assert "RuntimeError: the batched call failed on purpose" in str(result)
    # logged once for the call, not once per robot
    assert fleet.host.log().count("the batched call failed on purpose\n") <= 2
    fleet.set_fault(0, "none")
    fleet.assert_sessions_intact()


def test_a_crash_in_a_batched_call_fails_that_cycle_and_every_session_is_restored(
    fleet: Fleet,
) -> None:
    fleet.batched_round()
    fleet.set_fault(0, "crash")
    results = fleet.round()
    for result in results:
        assert isinstance(result, api.NoValidControl), results
        assert "exited with code 9 during compute_velocity_commands_batch" in str(result)
    fleet.clear_fault_once_back(0)
    fleet.assert_sessions_intact()
    restored = rf"batch:batch_planners:BatchEcho: worker \d+ restarted, {ROBOTS} session\(s\)"
    assert re.search(restored, fleet.host.log()), fleet.host.log()[-3000:]


def test_a_hang_in_a_batched_call_fails_that_cycle_and_the_worker_is_replaced(
    fleet: Fleet,
) -> None:
    fleet.batched_round()
    fleet.set_fault(1, "hang", sleep_s=30.0)
    results = fleet.round()
    for result in results:
        assert isinstance(result, api.NoValidControl), results
        assert "compute_velocity_commands_batch overran its 0.5 s deadline" in str(result)
    deadline = time.monotonic() + 30
    while "stayed stuck past its deadline and was killed" not in fleet.host.log():
        assert time.monotonic() < deadline, fleet.host.log()[-3000:]
        time.sleep(0.1)
    fleet.clear_fault_once_back(1)
    fleet.assert_sessions_intact()


def test_a_cycle_that_waited_a_control_period_is_not_computed(fleet: Fleet) -> None:
    fleet.set_fault(0, "hang", sleep_s=2 * PERIOD)  # under the 0.5 s deadline: no restart
    slow: list[Any] = []
    first = threading.Thread(target=lambda: slow.extend(fleet.round(fleet.clients[:1])))
    first.start()
    time.sleep(PERIOD / 4)  # robot 1's cycle queues behind the slow batch ...
    with pytest.raises(api.NoValidControl, match=r"overloaded: this control cycle waited \d+ ms"):
        fleet.clients[1].compute_velocity_commands(pose(), Twist())
    first.join(10)
    assert slow[0].twist.linear.x == SPEEDS[0]  # the slow one was served
    fleet.set_fault(0, "none")
    fleet.assert_sessions_intact()
    listed = nav2_pyif_tool("hosts", "--connect", fleet.host.endpoint, timeout=30)
    assert "not computed (overload): 1 waited a period, 0 superseded" in listed.stdout, listed


def test_robots_join_and_leave_while_others_cycle(fleet: Fleet) -> None:
    errors: list[Exception] = []
    served = [0, 0]
    stop = threading.Event()

    def drive(i: int) -> None:
        while not stop.is_set():
            try:
                cmd = fleet.clients[i].compute_velocity_commands(pose(), Twist())
                assert cmd.twist.linear.x == SPEEDS[i]
                served[i] += 1
            except Exception as exc:
                errors.append(exc)
            time.sleep(0.01)

    drivers = [threading.Thread(target=drive, args=(i,)) for i in (0, 1)]
    for t in drivers:
        t.start()
    try:
        for _ in range(3):  # robot 2 joins, cycles beside the others, leaves; again
            fleet.clients[2].close()
            joined = fleet.robot(2, speed=0.7, plan=7)
            fleet.clients[2] = joined
            sizes = set()
            for _ in range(15):
                cmd = joined.compute_velocity_commands(pose(), Twist())
                assert (cmd.twist.linear.x, cmd.twist.linear.y) == (0.7, 7.0)
                sizes.add(cmd.twist.angular.z)
            assert max(sizes) >= 2  # batched with the robots already there
            joined.deactivate()
            joined.cleanup()
    finally:
        stop.set()
        for t in drivers:
            t.join(10)
    assert not errors, errors[:3]
    assert min(served) > 20


def test_a_hot_swap_replaces_the_planner_of_its_batch_group_only(tmp_path: Path) -> None:
    other = "nav2_pyif/other/FollowPath"
    fleet = Fleet(
        tmp_path, "batch_planners:BatchEcho", f"--serve={other}=batch_planners:OtherBatchEcho"
    )
    try:
        outsider = ControllerClient(
            fleet.session, other, make_costmap(), params={"speed": 0.5}, timeouts=TIMEOUTS
        )
        assert outsider.wait_for_host(30)
        outsider.configure()
        outsider.activate()
        fleet.batched_round()
        message = request_reload(fleet.session, key(1), planner="batch_planners:BatchEchoV2")
        assert f"{ROBOTS} session(s) carried over" in message and "batch group" in message
        for i, cmd in enumerate(fleet.batched_round()):  # every key of the group, plans kept
            assert (cmd.twist.linear.x, cmd.twist.linear.y) == (2 * SPEEDS[i], PLAN_LENGTHS[i])
        assert outsider.compute_velocity_commands(pose(), Twist()).twist.linear.x == 0.5
        outsider.close()
    finally:
        fleet.close()


def test_config_entries_ask_for_batching_one_by_one(tmp_path: Path) -> None:
    planner = "batch_planners:BatchEcho"
    entries = [{"key": key(i), "planner": planner, "batch": True} for i in range(2)]
    host = PlannerHostProcess(
        [*entries, {"key": key(2), "planner": planner}],
        port=free_port(),
        log_level="INFO",
        log_path=tmp_path / "host.log",
        env=host_process(0, [], tmp_path / "unused.log").env,
    ).start()
    try:
        session = open_client_session(host.endpoint)
        client = ControllerClient(session, key(2), make_costmap(), timeouts=TIMEOUTS)
        assert client.wait_for_host(30), host.log()
        client.close()
        session.close()
        assert wait_until(lambda: f"on {key(2)}/**" in host.log())  # logged once it serves
        log = host.log()
        assert f"batch group: {planner} serves 2 key(s)" in log, log
        workers = re.findall(r"on (\S+)/\*\* \(controller, worker (\d+)\)", log)
        by_key = dict(workers)
        assert by_key[key(0)] == by_key[key(1)] != by_key[key(2)], workers
    finally:
        host.kill()
