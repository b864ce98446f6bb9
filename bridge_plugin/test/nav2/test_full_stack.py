"""The whole Nav2 stack: NavigateToPose through bt_navigator and the distribution's
default navigate_to_pose BT, with behavior_server's recoveries, controller_server with
PyController (the reference regulated pure pursuit, misbehaving on demand:
planners/fault_pursuit.py) and planner_server with PyGlobalPlanner (A*), each served by its
own planner host behind a `nav2-pyif router`. controller_server's failure_tolerance is 3 s
(bridge_plugin/params/nav2_pyif_params.yaml's value).

Each fault is repeated $NAV2_PYIF_FULL_STACK_RUNS times (default 20: a loop, not a retry), the
robot driving around the wall and back, and every navigation must succeed:
- none (the baseline; test_full_stack_native.py drives the same goals with Nav2's native RPP
  and NavFn);
- the controller's host SIGKILLed 3 s into a goal and restarted 2 s later;
- the controller hanging past the host's deadline (the worker killed and restarted);
- the controller raising NoValidControl for a second;
- the planner's host killed during a replan (the BT replans at 1 Hz) and restarted;
- a hot swap (SIGHUP) of the controller's host mid-navigation.
Per fault: successes, time to the goal (median, and extra over the baseline's median), the
number of recoveries the BT ran, and the longest stop while driving. The figures go to
$NAV2_PYIF_FIGURES (JSON) when set; tests/test_nav2_launch.py prints them.
"""

from __future__ import annotations

import os
import re
import signal
import statistics
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import nav2_testing
import pytest
from test_host_recovery import record

RUNS = int(os.environ.get("NAV2_PYIF_FULL_STACK_RUNS", "20"))
# Each test drives RUNS navigations of about 10 s (30 s with recoveries): the project's
# 120 s per-test timeout is for one navigation's worth.
pytestmark = pytest.mark.timeout(120 + 60 * RUNS)
FULL_STACK = (*nav2_testing.SERVERS, "behavior_server", "bt_navigator")
GOALS = ((2.0, 0.5), (0.0, 0.0))  # around the wall, and back
FAULT_AT = 3.0  # [s] into a navigation
CONTROLLER = (
    *("--path", str(nav2_testing.HERE / "planners")),
    *("--deadline", "0.5", "--hang-grace", "0.5"),
    *("--serve", f"{nav2_testing.PREFIX}/FollowPath=fault_pursuit:FaultPursuit"),
)
PLANNER = ("--serve", f"{nav2_testing.PREFIX}/GridBased=nav2_pyif_planners.astar:AStar")
BEHAVIOR = (
    "--serve",
    f"{nav2_testing.PREFIX}/backup=nav2_pyif_planners.free_backup:FreestBackUp",
)
BACKUP_BT = nav2_testing.HERE / "backup_recovery_bt.xml"


def full_stack_params(text: str) -> str:
    """nav2_params.yaml with bt_navigator and behavior_server, managed too, and
    failure_tolerance as the shipped params set it; the Python BackUp reaches its host as the
    other plugins do (zenoh-pico: zenoh_connect; zenoh-c: zenoh_config)."""
    text = text.replace("failure_tolerance: 0.0", "failure_tolerance: 3.0")
    zenoh = re.search(r"zenoh_(?:connect|config): .+", text)
    assert zenoh is not None, "nav2_params.yaml names no zenoh_connect or zenoh_config"
    text = text.replace(
        'node_names: ["controller_server", "planner_server"]',
        f"node_names: {list(FULL_STACK)!r}".replace("'", '"'),
    )
    added = (nav2_testing.HERE / "full_stack_params.yaml").read_text()
    if nav2_testing.is_lyrical():
        # Lyrical's bt_navigator refuses the old name ("MUST be removed") and takes prefixes
        names = "error_code_names:\n      - compute_path_error_code\n      - follow_path_error_code"
        assert names in added, "full_stack_params.yaml's error_code_names changed"
        prefixes = "error_code_name_prefixes:\n      - compute_path\n      - follow_path"
        added = added.replace(names, prefixes)
    return text + added.replace("@ZENOH@", zenoh.group(0))


def _through_a_router(procs: nav2_testing.Processes, endpoint: str) -> tuple[list[str], list[str]]:
    router = nav2_testing.project_command("nav2-pyif")
    assert router is not None, "nav2-pyif is not on PATH (or $NAV2_PYIF_RUN)"
    procs.start("router", [*router, "router", "--listen", endpoint])
    return [], ["--connect", endpoint]


@pytest.fixture(scope="module")
def stack(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    """The controller's host is bring_up's; the planner's a second host on the same router."""
    for up in nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_full_stack"),
        planners=CONTROLLER,
        edit_params=full_stack_params,
        topology=_through_a_router,
        servers=FULL_STACK,
    ):
        procs, endpoint = up["procs"], up["endpoint"]
        planner_host = [*(nav2_testing.host_command() or []), "--connect", endpoint, *PLANNER]

        def start_planner_host(procs: Any = procs, command: list[str] = planner_host) -> None:
            procs.start("planner_host_plans", command)

        start_planner_host()
        procs.start(
            "planner_host_behavior",
            [*(nav2_testing.host_command() or []), "--connect", endpoint, *BEHAVIOR],
        )
        NAVIGATIONS.clear()  # a new robot, at the origin
        client = up["client"]
        states = client.wait_active(FULL_STACK, 120.0)
        assert all(s == "active" for s in states.values()), f"{states}\n" + procs.log(
            "lifecycle_manager"
        )
        yield {**up, "start_planner_host": start_planner_host}


# Every goal sent to the stack now up, in order (its robot starts at GOALS[1], the origin).
NAVIGATIONS: list[tuple[float, float]] = []


@dataclass
class Run:
    succeeded: bool
    seconds: float
    recoveries: int
    longest_stop: float  # [s] between the first and the last moment the robot moved
    status: int
    faulted: bool  # the fault was made while the navigation ran


def _navigate(
    client: Any, goal: tuple[float, float], fault: Callable[[], None] | None, tree: str = ""
) -> Run:
    handle = client.navigate(*goal, behavior_tree=tree)
    started = time.monotonic()
    result_future = handle.get_result_async()
    faulted = False
    if fault is not None:
        client.spin_until(result_future.done, FAULT_AT)
        if not result_future.done():
            fault()
            faulted = True
    result = client.wait(result_future, 120.0)
    seconds = time.monotonic() - started
    client.recording = False
    status = -1 if result is None else int(result.status)
    return Run(
        status == nav2_testing.SUCCEEDED,
        seconds,
        client.recoveries,
        nav2_testing.longest_stop(client.speeds),
        status,
        faulted,
    )


def _runs(stack: dict[str, Any], fault: Callable[[], None] | None, tree: str = "") -> list[Run]:
    """RUNS navigations, each through ``fault`` at FAULT_AT s, with bt_navigator's default
    tree or the behaviour tree file ``tree``."""
    client, procs = stack["client"], stack["procs"]
    runs = []
    for _ in range(RUNS):
        # each navigation to the other goal, across the module's tests: never one that is
        # over before its fault
        goal = GOALS[len(NAVIGATIONS) % 2]
        NAVIGATIONS.append(goal)
        run = _navigate(client, goal, fault, tree)
        runs.append(run)
        assert fault is None or run.faulted, f"run {len(runs)} ended before its fault: {run}"
        logs = "\n".join(
            procs.log(n, 60) for n in ("bt_navigator", "controller_server", "planner_host")
        )
        assert run.succeeded, f"run {len(runs)} of {RUNS}: NavigateToPose ended {run}\n{logs}"
    return runs


BASELINE: list[float] = []  # the unfaulted runs' times, for the extra time of the others


def _record(name: str, runs: list[Run]) -> None:
    seconds = statistics.median(r.seconds for r in runs)
    figures: dict[str, float | int | str] = {
        f"full_stack_{name}_succeeded": f"{sum(r.succeeded for r in runs)}/{len(runs)}",
        f"full_stack_{name}_median_s": seconds,
        f"full_stack_{name}_max_recoveries": max(r.recoveries for r in runs),
        f"full_stack_{name}_median_longest_stop_s": statistics.median(r.longest_stop for r in runs),
        f"full_stack_{name}_max_longest_stop_s": max(r.longest_stop for r in runs),
    }
    if BASELINE:
        figures[f"full_stack_{name}_extra_s"] = seconds - statistics.median(BASELINE)
    record(**figures)
    print(name, figures)


def test_navigate_to_pose_through_the_python_plugins(stack: dict[str, Any]) -> None:
    runs = _runs(stack, None)
    BASELINE[:] = [r.seconds for r in runs]
    assert max(r.recoveries for r in runs) == 0, runs
    _record("none", runs)


def _kill_and_restart(stack: dict[str, Any], host: str, start: str) -> Callable[[], None]:
    """SIGKILL the planner host ``host`` (a name in the process set), start it again 2 s
    later through ``stack[start]``."""

    def fault() -> None:
        stack["procs"].kill(host, signal.SIGKILL)
        stack["client"].spin_until(lambda: False, 2.0)
        stack[start]()

    return fault


def test_a_killed_and_restarted_controller_host_costs_at_most_one_recovery(
    stack: dict[str, Any],
) -> None:
    runs = _runs(stack, _kill_and_restart(stack, "planner_host", "start_host"))
    _record("host_killed", runs)
    # a 2 s restart inside failure_tolerance: the robot waits, no spin or back-up
    assert max(r.recoveries for r in runs) <= 1, runs


def _fault_once(stack: dict[str, Any], kind: str, seconds: float = 1.0) -> Callable[[], None]:
    """Start FaultPursuit's ``kind`` for ``seconds`` through `ros2 param set`. The fault is
    set back to none first, so that setting it is a change on every run (not after: a hung
    worker refuses parameters until it is restarted)."""
    client = stack["client"]

    def fault() -> None:
        for name, value in (("fault", "none"), ("fault_for", seconds), ("fault", kind)):
            ok, reason = client.set_parameter("controller_server", f"FollowPath.{name}", value)
            assert ok, reason

    return fault


def test_a_controller_hanging_past_its_deadline(stack: dict[str, Any]) -> None:
    runs = _runs(stack, _fault_once(stack, "hang"))
    _record("hang", runs)
    assert max(r.recoveries for r in runs) <= 1, runs


def test_a_controller_raising_no_valid_control_for_a_second(stack: dict[str, Any]) -> None:
    runs = _runs(stack, _fault_once(stack, "no_valid_control", 1.0))
    _record("no_valid_control", runs)
    # inside failure_tolerance: controller_server holds the robot and keeps the goal
    assert max(r.recoveries for r in runs) == 0, runs


def test_the_planners_host_killed_during_a_replan(stack: dict[str, Any]) -> None:
    fault = _kill_and_restart(stack, "planner_host_plans", "start_planner_host")
    runs = _runs(stack, fault)
    _record("planner_host_killed", runs)


def test_a_hot_swap_mid_navigation(stack: dict[str, Any]) -> None:
    procs = stack["procs"]

    def swap() -> None:
        os.kill(procs.procs["planner_host"].pid, signal.SIGHUP)  # the host we started

    runs = _runs(stack, swap)
    _record("hot_swap", runs)
    assert max(r.recoveries for r in runs) == 0, runs


def test_the_behaviour_tree_recovers_with_the_python_backup(stack: dict[str, Any]) -> None:
    """The controller fails for longer than failure_tolerance (PatienceExceeded), and the
    tree's recovery, BackUp, is behavior_server's PyBackUp, served by FreestBackUp."""
    procs = stack["procs"]

    def backups() -> tuple[int, int]:
        """behavior_server's BackUps so far: begun, completed successfully."""
        log = procs.log("behavior_server", 100_000)
        return log.count("Running backup"), log.count("backup completed successfully")

    before = backups()
    runs = _runs(stack, _fault_once(stack, "no_valid_control", 4.0), str(BACKUP_BT))
    _record("python_backup", runs)
    # One BackUp per navigation, each successful (read from behavior_server's log: the
    # feedback's number_of_recoveries can miss its last update before the result)
    begun, completed = (now - then for now, then in zip(backups(), before, strict=True))
    assert begun == completed == len(runs), (begun, completed, runs)
    assert "behavior_server/backup" in procs.log("planner_host_behavior", 400)
