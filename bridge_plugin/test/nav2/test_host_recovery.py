"""How fast Nav2 notices a lost planner host and moves again once one is back
(RELIABILITY.md "Recovery in Nav2"), through the deployment guide's router topology: a
`nav2-pyif router` on the robot (on rmw_zenoh: ROS's own router, which Nav2's traffic, the
plugins and the host then share), the plugins its clients, the planner host on another
"machine" (a network namespace behind a veth link; where namespaces cannot be made, the host
runs here and its machine vanishing is a SIGSTOP: no packet, no closed connection either).

1. The host's machine vanishes mid-goal: the goal aborts, and the plugin logs the host gone
   about one Zenoh lease (1 s) after the last packet, not after the default 10 s; when the
   link comes back the host is alive again by itself and the next goal succeeds.
2. The host is killed (SIGKILL) mid-goal and restarted: the times from its start to "ready",
   and from "ready" to the robot moving again (a goal re-sent as soon as the last failed, as
   a behaviour tree's retry does).

The figures go to $NAV2_PYIF_FIGURES (JSON) when set; tests/test_nav2_launch.py prints them.
Needs what test_nav2_pyif.py needs, and `nav2-pyif` (through $NAV2_PYIF_RUN or on PATH).
"""

from __future__ import annotations

import json
import os
import signal
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_testing
import pytest

from tests.netns import Link, namespace_link

GOAL_A, GOAL_B = (2.0, 0.5), (0.0, 0.0)
SUBNET = "10.231.9"  # not test_network's: both may exist at once


def record(**figures: float | int | str) -> None:
    path = os.environ.get("NAV2_PYIF_FIGURES")
    if not path:
        return
    known = json.loads(Path(path).read_text()) if Path(path).exists() else {}
    known.update({k: round(v, 3) if isinstance(v, float) else v for k, v in figures.items()})
    Path(path).write_text(json.dumps(known, indent=1))


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    router = nav2_testing.project_command("nav2-pyif")
    if router is None:
        pytest.skip("the Nav2 recovery test needs nav2-pyif on PATH or $NAV2_PYIF_RUN")
    shared = nav2_testing.shared_router()  # rmw_zenoh's own router: ROS, plugins and host
    with namespace_link_or_none() as link:

        def through_a_router(
            procs: nav2_testing.Processes, endpoint: str
        ) -> tuple[list[str], list[str]]:
            """The router listens on the plugins' endpoint (and on the link); the host, in
            its namespace, connects to it. On rmw_zenoh the router is ROS's own, already
            listening on every interface."""
            port = endpoint.rsplit(":", 1)[1]
            remote = f"tcp/{link.subnet}.1:{port}" if link else endpoint
            if not shared:
                extra = ["--listen", remote] if link else []
                procs.start("router", [*router, "router", "--listen", endpoint, *extra])
            inside = ["ip", "netns", "exec", link.ns] if link else []
            return inside, ["--connect", remote]

        for up in nav2_testing.bring_up(
            tmp_path_factory.mktemp("nav2_host_recovery"),
            topology=through_a_router,
            endpoint=shared,
        ):
            yield {**up, "link": link}


class namespace_link_or_none:  # noqa: N801  (used as a context manager, like namespace_link)
    """The host's own network namespace where this machine allows one, else None."""

    def __enter__(self) -> Link | None:
        self._context: Any = namespace_link(SUBNET)
        try:
            return self._context.__enter__()  # type: ignore[no-any-return]
        except pytest.skip.Exception:
            self._context = None
            return None

    def __exit__(self, *exc: object) -> None:
        if self._context is not None:
            self._context.__exit__(*exc)


def _plan_and_follow(client: Any, goal: tuple[float, float], patience: float) -> Any:
    """ComputePathToPose then FollowPath, the plan re-requested as soon as one fails (as a
    behaviour tree retries) until `patience` runs out; the FollowPath goal handle."""
    end = time.monotonic() + patience
    while True:
        planned = client.plan(*goal)
        if planned is not None and planned.status == nav2_testing.SUCCEEDED:
            return client.follow(planned.result.path)
        assert time.monotonic() < end, f"no plan within {patience} s: {planned}"
        client.spin_until(lambda: False, 0.02)


def _gone_after(procs: nav2_testing.Processes, client: Any, since: float) -> float | None:
    words = f"is gone from {nav2_testing.PREFIX}/FollowPath"
    client.spin_until(lambda: procs.logged_at("controller_server", words, since), 15.0)
    stamp = procs.logged_at("controller_server", words, since)
    return None if stamp is None else stamp - since


def test_a_vanished_host_is_noticed_within_a_lease_and_comes_back_by_itself(
    nav2: dict[str, Any],
) -> None:
    client, procs, link = nav2["client"], nav2["procs"], nav2["link"]
    states = client.wait_active(nav2_testing.SERVERS, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + procs.log("router")
    handle = _plan_and_follow(client, GOAL_A, 30.0)
    assert client.spin_until(lambda: client.speed > 0.01, 10.0), procs.log("controller_server")
    client.spin_until(lambda: False, 1.0)  # driving

    vanished = time.time()
    if link is not None:
        link.cut()
    else:
        os.killpg(procs.procs["planner_host"].pid, signal.SIGSTOP)
    result = client.wait(handle.get_result_async(), 30.0)
    aborted = time.time() - vanished
    logs = procs.log("controller_server")
    assert result is not None and result.status == nav2_testing.ABORTED, f"{result}\n{logs}"
    code = nav2_testing.error_code(result.result)  # None on Humble
    noticed = _gone_after(procs, client, vanished)
    assert noticed is not None, "the plugin never logged the host gone\n" + logs
    assert noticed < 5.0, f"the host was noticed gone only after {noticed:.1f} s"

    restored = time.time()
    if link is not None:
        link.restore()
    else:
        os.killpg(procs.procs["planner_host"].pid, signal.SIGCONT)
    words = f"is alive on {nav2_testing.PREFIX}/FollowPath"
    assert client.spin_until(lambda: procs.logged_at("controller_server", words, restored), 30.0), (
        procs.log("controller_server") + procs.log("planner_host")
    )
    back = procs.logged_at("controller_server", words, restored)
    assert back is not None
    handle = _plan_and_follow(client, GOAL_B, 30.0)
    result = client.wait(handle.get_result_async(), 90.0)
    assert result is not None and result.status == nav2_testing.SUCCEEDED, procs.log(
        "controller_server"
    )
    record(
        vanish_method="veth link down" if link is not None else "SIGSTOP",
        vanish_goal_aborted_s=aborted,
        vanish_host_gone_logged_s=noticed,
        vanish_abort_error_code=code,
        link_back_host_alive_logged_s=back - restored,
    )


def test_a_killed_host_restarted_serves_again_quickly(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    handle = _plan_and_follow(client, GOAL_A, 30.0)
    assert client.spin_until(lambda: client.speed > 0.01, 10.0), procs.log("controller_server")
    client.spin_until(lambda: False, 1.0)  # driving
    killed = time.time()
    procs.kill("planner_host", signal.SIGKILL)
    result = client.wait(handle.get_result_async(), 30.0)
    aborted = time.time() - killed
    assert result is not None and result.status == nav2_testing.ABORTED, procs.log(
        "controller_server"
    )
    noticed = _gone_after(procs, client, killed)
    assert noticed is not None, procs.log("controller_server")
    client.spin_until(lambda: client.speed < 0.01, 5.0)  # Nav2 stopped the robot

    started = nav2["start_host"]()
    assert client.spin_until(lambda: procs.logged_at("planner_host", "ready (", started), 30.0), (
        procs.log("planner_host")
    )
    ready = procs.logged_at("planner_host", "ready (", started)
    assert ready is not None
    handle = _plan_and_follow(client, GOAL_A, 30.0)
    assert client.spin_until(lambda: client.speed > 0.01, 10.0), procs.log("controller_server")
    moving = time.time()
    seen = procs.logged_at("controller_server", "is alive on", started)
    result = client.wait(handle.get_result_async(), 90.0)
    assert result is not None and result.status == nav2_testing.SUCCEEDED, procs.log(
        "controller_server"
    )
    record(
        kill_goal_aborted_s=aborted,
        kill_host_gone_logged_s=noticed,
        restart_ready_s=ready - started,
        restart_plugin_saw_host_after_ready_s=(seen - ready) if seen else float("nan"),
        restart_robot_moving_after_ready_s=moving - ready,
    )
