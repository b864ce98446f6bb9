"""End to end through real planner-host processes and real Zenoh sessions on loopback."""

from __future__ import annotations

import logging
import math
import threading
import time
from pathlib import Path
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif import GoalTolerances, Plan
from nav2_pyif.client import ControllerClient, GlobalPlannerClient, Timeouts

from tests.conftest import make_costmap

pytestmark = pytest.mark.integration

KEY = "nav2_pyif/test_robot/FollowPath"
PLANNER_KEY = "nav2_pyif/test_robot/GridBased"
GENEROUS = Timeouts(call=2.0, lifecycle=5.0, configure=10.0, plan=5.0)


def pose(x: float = 1.0, y: float = 1.0, frame: str = "odom") -> Any:
    msg = PoseStamped()
    msg.header.frame_id = frame
    msg.pose.position.x, msg.pose.position.y = x, y
    msg.pose.orientation.w = 1.0
    return msg


def controller(zsession_factory: Any, host: Any, **kwargs: Any) -> ControllerClient:
    kwargs.setdefault("timeouts", GENEROUS)
    client = ControllerClient(
        zsession_factory(host.endpoint), kwargs.pop("key", KEY), make_costmap(), **kwargs
    )
    assert client.wait_for_host(15), host.log()
    return client


def test_full_controller_session(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    client = controller(zsession_factory, host, params={"gain": 2}, record_calls=True)
    assert client.configure() == {"gain": 2.0, "label": "echo"}
    client.activate()
    client.set_plan(Plan(np.column_stack([np.linspace(0, 3, 40), np.zeros(40)]), "odom"))
    checker = GoalTolerances(0.25, 0.3, 0.05, 0.1)
    cmd = client.compute_velocity_commands(pose(), Twist(), checker)
    assert cmd.header.frame_id == "base_link"
    lin, ang = cmd.twist.linear, cmd.twist.angular
    assert (lin.x, lin.y, lin.z, ang.x, ang.y, ang.z) == (40.0, 2.0, -1.0, 1.0, 0.0, 1.0)
    client.set_speed_limit(0.4, False)
    assert client.set_parameters({"gain": 5.0, "label": 3}) == {
        "label": "label: expected str, got int"
    }
    cmd = client.compute_velocity_commands(pose(2.5, 2.5), Twist())
    assert (cmd.twist.linear.y, cmd.twist.linear.z) == (5.0, 0.4)
    assert cmd.twist.angular.y == api.Costmap.LETHAL  # the pose is in the lethal quadrant
    assert client.cancel() is True
    client.reset()
    client.deactivate()
    client.cleanup()
    with pytest.raises(api.ControllerException, match="before configure"):
        client.compute_velocity_commands(pose(), Twist())
    assert client.resyncs == 0
    assert host.stop() == 143  # SIGTERM: a clean stop, exit 128 + 15


def test_costmap_travels_only_when_changed(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    client = controller(zsession_factory, host, record_calls=True)
    client.configure()
    client.activate()
    sizes = []
    for version in (1, 1, 2, 2, 3):
        if version != client.costmap.version:
            client.update_costmap(make_costmap(version=version))
        cmd = client.compute_velocity_commands(pose(), Twist())
        assert cmd.twist.angular.x == version  # the planner sees the current version
        assert client.records is not None
        sizes.append(client.records[-1].request_bytes)
    small, big = min(sizes), 40 * 40
    assert sizes[0] == sizes[1] == sizes[3] == small < big  # unchanged: no costmap
    assert sizes[2] > big and sizes[4] > big  # changed: the 40x40 grid travels


def test_planner_session_and_cancellation(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", PLANNER_KEY, "--planner", "echo_planners:LinePlanner")
    client = GlobalPlannerClient(
        zsession_factory(host.endpoint),
        PLANNER_KEY,
        make_costmap(),
        params={"points": 25},
        timeouts=GENEROUS,
    )
    assert client.wait_for_host(15)
    client.configure()
    client.activate()
    plan = client.create_plan(pose(0.0, 0.0), pose(2.0, 1.0))
    assert len(plan) == 25 and plan.frame_id == "odom"
    assert np.allclose(plan.xy[-1], [2.0, 1.0])
    with pytest.raises(api.GoalOccupied, match="goal is in a wall"):
        client.set_parameters({"mode": "occupied"})
        client.create_plan(pose(), pose())
    client.set_parameters({"mode": "slow"})
    cancel_at = time.monotonic() + 0.2
    started = time.monotonic()
    with pytest.raises(api.PlannerCancelled):
        client.create_plan(pose(), pose(), cancel_checker=lambda: time.monotonic() > cancel_at)
    assert time.monotonic() - started < 2.0  # cancelled, not the planner's 10 s
    client.set_parameters({"mode": "ok"})
    assert len(client.create_plan(pose(), pose(3.0, 3.0))) == 25


PLAN_TIMEOUTS = Timeouts(call=0.5, lifecycle=5.0, configure=20.0, plan=8.0)


def active_planner(
    start_host: Any, zsession_factory: Any, *host_args: str
) -> tuple[Any, GlobalPlannerClient]:
    """A planner host started with ``host_args`` and an active client of it (PLAN_TIMEOUTS)."""
    host = start_host(*host_args)
    client = GlobalPlannerClient(
        zsession_factory(host.endpoint), PLANNER_KEY, make_costmap(), timeouts=PLAN_TIMEOUTS
    )
    assert client.wait_for_host(15)
    client.configure()
    client.activate()
    return host, client


def plan_across(client: GlobalPlannerClient, delay: float, event: Any) -> tuple[Any, float]:
    """create_plan with ``event()`` (a host's kill, a restart) run ``delay`` s into it: the
    plan and how long the call took [s]."""
    timer = threading.Timer(delay, event)
    started = time.monotonic()
    timer.start()
    try:
        plan = client.create_plan(pose(0.0, 0.0), pose(2.0, 1.0))
    finally:
        timer.join()
    return plan, time.monotonic() - started


def test_a_plan_waits_for_a_restarting_host_within_its_timeout_and_a_cycle_does_not(
    start_host: Any, zsession_factory: Any
) -> None:
    """planner_server runs create_plan in its own thread while the robot follows its last
    path: a host restart there costs a slow plan, not a recovery. The control loop's calls
    fail at once (the controller server's failure_tolerance rides those out)."""
    args = ("--key", PLANNER_KEY, "--planner", "echo_planners:LinePlanner")
    host, client = active_planner(start_host, zsession_factory, *args)
    timeouts = PLAN_TIMEOUTS
    host.kill()
    assert client.hosts.wait_for(lambda alive: not alive, 10)
    restarted: list[Any] = []
    plan, took = plan_across(
        client, 1.0, lambda: restarted.append(start_host(*args, port=host.port))
    )
    assert len(plan) > 1 and took > 1.0  # it waited for the new host
    assert client.resyncs == 1  # and re-established the session there

    short = GlobalPlannerClient(
        zsession_factory(host.endpoint), PLANNER_KEY, make_costmap(), timeouts=timeouts
    )
    assert short.wait_for_host(15)
    short.configure()
    restarted[0].kill()
    assert short.hosts.wait_for(lambda alive: not alive, 10)
    started = time.monotonic()
    with pytest.raises(api.PlannerException, match="no planner host is alive"):
        short.create_plan(pose(), pose(1.0, 1.0))
    assert time.monotonic() - started >= timeouts.plan * 0.9  # no host came: its timeout

    ctrl_host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    ctrl = controller(zsession_factory, ctrl_host)
    ctrl.configure()
    ctrl_host.kill()
    assert ctrl.hosts.wait_for(lambda alive: not alive, 10)
    started = time.monotonic()
    with pytest.raises(api.NoValidControl, match="no planner host is alive"):
        ctrl.compute_velocity_commands(pose(), Twist())
    assert time.monotonic() - started < 0.5  # at once


def test_a_plan_whose_host_dies_in_the_call_is_sent_again_to_its_restart(
    start_host: Any, zsession_factory: Any
) -> None:
    """The host is killed with create_plan in it: the query ends at once with no reply. Within
    the plan's timeout the call waits for a host to come back and is sent again there (the
    session re-established first), as the C++ plugin does: no recovery in Nav2."""
    host, client = active_planner(
        start_host, zsession_factory, "--key", PLANNER_KEY, "--planner", "echo_planners:LinePlanner"
    )
    client.set_parameters({"mode": "slow"})  # the planner would take 10 s
    first = client.host
    restarted: list[Any] = []

    def kill_and_restart() -> None:
        host.kill()  # SIGKILL, 0.5 s into the plan
        restarted.append(
            start_host(
                "--key", PLANNER_KEY, "--planner", "echo_planners:QuickLinePlanner", port=host.port
            )
        )

    plan, took = plan_across(client, 0.5, kill_and_restart)
    assert len(plan) == 11 and np.allclose(plan.xy[-1], [2.0, 1.0])  # the new host's plan
    assert took < PLAN_TIMEOUTS.plan
    assert client.resyncs == 1 and client.host not in (None, first) and restarted


def test_errors_cross_the_wire_typed_with_traceback(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:FaultyController")
    client = controller(zsession_factory, host)
    client.configure()
    client.activate()
    client.set_parameters({"fault": "FailedToMakeProgress"})
    with pytest.raises(api.FailedToMakeProgress) as info:
        client.compute_velocity_commands(pose(), Twist())
    assert "compute_velocity_commands" in info.value.remote_traceback
    client.set_parameters({"fault": "nan"})
    with pytest.raises(api.NoValidControl, match="non-finite"):
        client.compute_velocity_commands(pose(), Twist())
    client.set_parameters({"fault": "zero_division"})
    with pytest.raises(api.ControllerException, match="ZeroDivisionError") as generic:
        client.compute_velocity_commands(pose(), Twist())
    assert generic.value.python_type == "builtins.ZeroDivisionError"
    client.set_parameters({"fault": "none"})
    assert client.compute_velocity_commands(pose(), Twist()).twist.angular.z > 0
    log = host.log()
    assert log.count("compute_velocity_commands failed [ControllerException]") == 1  # once
    assert "return 1 / 0" in log  # with the traceback
    assert "Traceback (most recent call last)" in log


def test_host_restart_mid_session_restores_the_plan(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    client = controller(zsession_factory, host, params={"gain": 4.0})
    client.configure()
    client.activate()
    client.set_plan(Plan(np.zeros((17, 3)), "odom"))
    client.set_speed_limit(30.0, True)
    client.set_parameters({"gain": 6.0})
    assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == 17.0
    host.kill()  # SIGKILL: nothing is saved by the host
    assert client.hosts.wait_for(lambda alive: not alive, 10)
    with pytest.raises(api.NoValidControl, match="no planner host is alive"):
        client.compute_velocity_commands(pose(), Twist())
    restarted = start_host(
        "--key", KEY, "--planner", "echo_planners:EchoController", port=host.port
    )
    assert client.wait_for_host(15), restarted.log()
    cmd = client.compute_velocity_commands(pose(), Twist())
    assert cmd.twist.linear.x == 17.0  # plan restored
    assert cmd.twist.linear.y == 6.0  # parameter change restored
    assert cmd.twist.linear.z == 30.0  # speed limit restored
    assert client.resyncs == 1 and client.epoch == 2


def test_no_host_fails_fast(zsession_factory: Any) -> None:
    from tests.conftest import free_port

    session = zsession_factory(f"tcp/127.0.0.1:{free_port()}")
    client = ControllerClient(session, KEY, make_costmap(), timeouts=Timeouts(configure=5.0))
    started = time.monotonic()
    with pytest.raises(api.NoValidControl, match="no planner host is alive"):
        client.configure()
    assert time.monotonic() - started < 0.5  # no 5 s timeout wait


def test_a_hung_call_times_out_and_the_next_call_works(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:FaultyController")
    client = controller(zsession_factory, host, timeouts=Timeouts(call=0.3, lifecycle=5.0))
    client.configure()
    client.set_parameters({"fault": "sleep", "sleep_s": 0.6})  # host deadline: 1 s
    started = time.monotonic()
    with pytest.raises(api.NoValidControl, match="no reply"):
        client.compute_velocity_commands(pose(), Twist())
    assert time.monotonic() - started < 0.9
    client.set_parameters({"fault": "none"})  # queued behind the slow call, then applied
    assert math.isfinite(client.compute_velocity_commands(pose(), Twist()).twist.linear.x)


def test_several_planners_on_one_host_and_delegates(start_host: Any, zsession_factory: Any) -> None:
    delegate_key = "nav2_pyif/robot2/FollowPath"
    host = start_host(
        "--serve",
        f"{KEY}=echo_planners:EchoController",
        "--serve",
        f"{PLANNER_KEY}=echo_planners:LinePlanner",
        "--key",
        delegate_key,
        "--module",
        "seed_delegates",
        "--delegate",
        "compute_velocity_commands=compute,set_plan=on_plan",
        "--delegate",
        "set_speed_limit=on_limit",
    )
    session = zsession_factory(host.endpoint)
    ctrl = ControllerClient(session, KEY, make_costmap(), timeouts=GENEROUS)
    plnr = GlobalPlannerClient(session, PLANNER_KEY, make_costmap(), timeouts=GENEROUS)
    seed = ControllerClient(session, delegate_key, make_costmap(size=12), timeouts=GENEROUS)
    for client in (ctrl, plnr, seed):
        assert client.wait_for_host(15), host.log()
        client.configure()
        client.activate()
    plan = plnr.create_plan(pose(0, 0), pose(1, 1))
    ctrl.set_plan(plan)
    seed.set_plan(plan)
    seed.set_speed_limit(0.7, False)
    assert ctrl.compute_velocity_commands(pose(), Twist()).twist.linear.x == len(plan)
    cmd = seed.compute_velocity_commands(pose(), Twist())
    assert (cmd.twist.linear.x, cmd.twist.linear.y, cmd.twist.angular.z) == (11.0, 0.7, 12.0)


def test_concurrent_sessions_on_one_key_are_isolated(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    session = zsession_factory(host.endpoint)
    clients = [ControllerClient(session, KEY, make_costmap(), timeouts=GENEROUS) for _ in range(4)]
    errors: list[BaseException] = []

    def run(index: int, client: ControllerClient) -> None:
        try:
            assert client.wait_for_host(15)
            client.configure()
            client.set_plan(Plan(np.zeros((index + 2, 3)), "odom"))
            for _ in range(50):
                assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == index + 2
        except BaseException as exc:
            errors.append(exc)

    threads = [threading.Thread(target=run, args=(i, c)) for i, c in enumerate(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    assert not errors, errors


def test_a_speed_limit_set_while_no_host_is_up_survives(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    client = controller(zsession_factory, host)
    client.configure()
    client.activate()
    client.set_plan(Plan(np.zeros((9, 3)), "odom"))
    host.kill()
    assert client.hosts.wait_for(lambda alive: not alive, 10)
    with pytest.raises(api.NoValidControl, match="no planner host is alive"):
        client.set_speed_limit(0.15, False)  # a slow zone starts while the host is down
    start_host("--key", KEY, "--planner", "echo_planners:EchoController", port=host.port)
    assert client.wait_for_host(15)
    cmd = client.compute_velocity_commands(pose(), Twist())
    assert (cmd.twist.linear.x, cmd.twist.linear.z) == (9.0, 0.15)  # plan and limit re-sent
    client.cleanup()
    client.configure()
    assert client.compute_velocity_commands(pose(), Twist()).twist.linear.z == -1.0  # forgotten


def test_a_plan_set_while_the_host_is_down_is_kept_and_sent_first_not_raised(
    start_host: Any, zsession_factory: Any
) -> None:
    """Nav2's behaviour tree replans about once a second: a set_plan that raised while the host
    restarts would end FollowPath at once, outside the controller server's failure_tolerance."""
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    client = controller(zsession_factory, host)
    client.configure()
    client.activate()
    client.set_plan(Plan(np.zeros((9, 3)), "odom"))
    host.kill()
    assert client.hosts.wait_for(lambda alive: not alive, 10)
    failure = client.set_plan(Plan(np.zeros((12, 3)), "odom"))
    assert isinstance(failure, api.NoValidControl) and failure.host_failed, failure
    with pytest.raises(api.NoValidControl, match="no planner host is alive"):
        client.compute_velocity_commands(pose(), Twist())  # the cycle fails, as it would alone
    start_host("--key", KEY, "--planner", "echo_planners:EchoController", port=host.port)
    assert client.wait_for_host(15)
    assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == 12.0
    assert client.set_plan(Plan(np.zeros((5, 3)), "odom")) is None


def warned(log: str, words: str) -> bool:
    return any("[WARNING]" in line and words in line for line in log.splitlines())


def test_delegate_modules_bind_by_name_and_say_what_a_missing_role_means(
    start_host: Any, zsession_factory: Any, tmp_path: Path
) -> None:
    """Function-delegate modules: ``--module m`` alone binds m's functions named after the roles;
    the roles left without a function are said once at start, at INFO, with what Nav2's call
    then does: no warning names a role the user never bound."""
    by_name, one_liner = "nav2_pyif/apf/FollowPath", "nav2_pyif/seed/FollowPath"
    config = tmp_path / "planners.yaml"
    config.write_text(
        f"planners:\n  - {{key: {by_name}, module: nav2_pyif_planners.apf}}\n"
        f"  - {{key: {one_liner}, module: seed_delegates, "
        "delegates: {compute_velocity_commands: compute}}\n"
    )
    host = start_host("--config", str(config))
    apf = controller(zsession_factory, host, key=by_name)
    assert "lookahead" in apf.configure()  # the module's configure(params) was bound
    apf.set_plan(Plan(np.column_stack([np.linspace(0, 1, 20), np.zeros(20)]), "odom"))
    # the APF raises NoValidControl unless its set_plan was bound
    assert apf.compute_velocity_commands(pose(0.1, 0.0), Twist()).twist.linear.x > 0.0
    log = host.log()
    assert (
        "nav2_pyif_planners.apf: functions bound by name: compute_velocity_commands, "
        "configure, set_plan, set_speed_limit" in log
    )
    assert "[WARNING]" not in log, log
    defaults = [line for line in log.splitlines() if "roles left to their default" in line]
    apf_line, seed_line = (
        next(line for line in defaults if f"{module}: roles" in line)
        for module in ("nav2_pyif_planners.apf", "seed_delegates")
    )
    assert "[INFO]" in apf_line and "set_plan has no delegate" not in apf_line
    assert "activate has no delegate: Nav2's activate does nothing" in apf_line
    for role, meaning in [
        ("set_plan", "Nav2's global plan reaches your functions only as compute_velocity_comm"),
        ("set_speed_limit", "Nav2's speed limits (speed filter zones) never reach your functions"),
        ("configure", "your functions get no Parameters"),
        ("cancel", "a cancel is answered at once as done"),
    ]:
        assert f"{role} has no delegate: {meaning}" in seed_line, seed_line


def test_a_misspelt_parameter_is_reported_and_an_undeclared_update_refused(
    start_host: Any, zsession_factory: Any, caplog: pytest.LogCaptureFixture
) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    client = controller(zsession_factory, host, params={"gain": 2.0, "gian": 3.0})
    with caplog.at_level(logging.WARNING, logger="nav2_pyif.client"):
        assert client.configure() == {"gain": 2.0, "label": "echo"}
    reason = "gian is not a parameter of this planner (did you mean gain?)"
    assert client.undeclared == {"gian": reason}  # in the configure reply
    warning = f"{reason}; it declares: gain, label"
    assert f"FollowPath: the planner ignores parameter(s) gian: {warning}" in caplog.text
    assert warned(host.log(), f"parameters given but never declared, ignored: {warning}")
    # as ROS 2 does: an update to a parameter the planner does not declare is refused
    assert client.set_parameters({"gain": 4.0, "lable": "x"}) == {
        "lable": "lable is not a parameter of this planner (did you mean label?); "
        "it declares: gain, label"
    }
    assert client.compute_velocity_commands(pose(), Twist()).twist.linear.y == 4.0


def test_nested_keys_answer_only_their_own_calls_and_a_wildcard_query_is_ignored(
    start_host: Any, zsession_factory: Any
) -> None:
    """A key nested under another (allowed, if unusual) is answered by its own planner alone,
    and a wildcard query over a key (or its admin keys) gets no reply rather than a wrong one."""
    inner = f"{KEY}/inner"
    host = start_host(
        "--serve",
        f"{KEY}=echo_planners:EchoController",
        "--serve",
        f"{inner}=echo_planners:LinePlanner",
    )
    session = zsession_factory(host.endpoint)
    outer_client = ControllerClient(session, KEY, make_costmap(), timeouts=GENEROUS)
    inner_client = GlobalPlannerClient(session, inner, make_costmap(), timeouts=GENEROUS)
    for client in (outer_client, inner_client):
        assert client.wait_for_host(15), host.log()
        client.configure()
        client.activate()
    assert len(inner_client.create_plan(pose(0, 0), pose(1, 1))) > 1  # only a planner plans
    assert outer_client.compute_velocity_commands(pose(), Twist()).header.frame_id == "base_link"
    for wildcard in (f"{KEY}/**", f"{KEY}/admin/*"):
        replies = list(session.get(wildcard, timeout=2.0))
        assert replies == [], [str(r.ok.key_expr) if r.ok else r.err for r in replies]
    assert "Traceback" not in host.log()
