"""Signals: every long-running command, sent SIGINT, SIGTERM or SIGHUP, stops its children
(planner host, workers, the multiprocessing resource tracker, client processes), removes its
temporary files, writes what it has and exits with 128 + the signal's number, without a
traceback. planner-host reloads on SIGHUP instead."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
import zenoh
from geometry_msgs.msg import Twist
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.zenoh_config import ZenohOptions, open_session
from nav2_pyif.exceptions import NoValidControl
from nav2_pyif.params import ParamValue
from PIL import Image

from tests.conftest import (
    FIXTURES,
    free_port,
    make_costmap,
    process_tree,
    survivors,
    wait_until,
)
from tests.test_host_e2e import GENEROUS, pose

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]
SIGNALS = [signal.SIGINT, signal.SIGTERM, signal.SIGHUP]
WORKER, TRACKER = "spawn_main", "resource_tracker"


class Command:
    """A command run in its own process group (a signal reaches it alone, as ``kill PID``
    does), with TMPDIR pointed at a directory of its own."""

    def __init__(self, tmp_path: Path, *argv: str) -> None:
        self.tmp = tmp_path / "tmpdir"
        self.tmp.mkdir()
        self.output = tmp_path / "output.txt"
        with open(self.output, "wb") as out:
            self.proc = subprocess.Popen(
                list(argv),
                stdout=out,
                stderr=subprocess.STDOUT,
                env=dict(
                    os.environ,
                    TMPDIR=str(self.tmp),
                    PYTHONPATH=os.pathsep.join([str(FIXTURES), os.environ.get("PYTHONPATH", "")]),
                ),
                start_new_session=True,
            )
        self.tree: dict[int, tuple[str, str]] = {}

    def text(self) -> str:
        return self.output.read_text(errors="replace")

    def wait_for(self, *, children: dict[str, int], words: str = "", timeout: float = 60) -> None:
        """Until its descendants include ``children`` (command-line part -> how many) and its
        output says ``words``; remembers the descendants."""

        def ready() -> bool:
            assert self.proc.poll() is None, self.text()
            self.tree = process_tree(self.proc.pid)
            commands = [c for _, c in self.tree.values()]
            enough = all(sum(p in c for c in commands) >= n for p, n in children.items())
            return enough and words in self.text()

        assert wait_until(ready, timeout), f"{self.tree}\n{self.text()}"

    def signal_and_wait(self, signum: int, timeout: float = 30) -> int:
        self.tree.update(process_tree(self.proc.pid))
        self.proc.send_signal(signum)
        try:
            return self.proc.wait(timeout)
        finally:
            if self.proc.poll() is None:
                os.killpg(self.proc.pid, signal.SIGKILL)

    def assert_ended_cleanly(self, code: int, signum: int) -> None:
        text = self.text()
        assert code == 128 + signum, f"exit {code}\n{text}"
        assert "Traceback" not in text, text
        assert wait_until(lambda: not survivors(self.tree), 10), survivors(self.tree)
        assert list(self.tmp.iterdir()) == []


def python(*args: str) -> list[str]:
    return [sys.executable, "-m", *args]


@pytest.mark.parametrize(
    ("via", "signum"),
    # the wrapper execs the same command: one signal shows it does
    [*(("nav2-pyif", s) for s in SIGNALS), ("scripts/sim.sh", signal.SIGTERM)],
    ids=lambda v: v.name if isinstance(v, signal.Signals) else v,
)
def test_sim_stops_its_host_and_writes_the_run_so_far(
    tmp_path: Path, signum: int, via: str
) -> None:
    out = tmp_path / "out"
    prefix = (
        [str(ROOT / "scripts/sim.sh")]
        if via != "nav2-pyif"
        else python("nav2_pyif.tools.main", "sim")
    )
    # real time, so that it still drives when the signal comes; a generous call timeout, so
    # that a loaded machine does not end the run first
    realtime = ("--realtime", "--call-timeout", "1")
    sim = Command(tmp_path, *prefix, *realtime, "--no-progress", "--out", str(out))
    # the host, a worker per planner and the resource tracker; then let it drive a while
    sim.wait_for(children={"nav2_pyif.server.cli": 1, WORKER: 2, TRACKER: 1}, words="driving with")
    time.sleep(1.0)
    sim.assert_ended_cleanly(sim.signal_and_wait(signum), signum)
    name = signal.Signals(signum).name
    record = json.loads((out / "office_pure_pursuit.json").read_text())
    assert record["summary"]["outcome"] == f"interrupted by {name}"
    assert record["summary"]["reached"] is False and record["trajectory"]
    with Image.open(out / "office_pure_pursuit.png") as png:
        assert f"interrupted by {name}" in png.text["Title"]
    assert f"interrupted by {name}; wrote the run so far" in sim.text()


KEY = "nav2_pyif/sig/FollowPath"


def host_command(endpoint: str, planner: str = "EchoController", *extra: str) -> list[str]:
    return python(
        "nav2_pyif.server.cli",
        *("--listen", endpoint, "--log-level", "INFO"),
        *("--key", KEY, "--planner", f"echo_planners:{planner}", *extra),
    )


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=lambda s: s.name)
def test_planner_host_stops_its_workers(tmp_path: Path, signum: int) -> None:
    host = Command(tmp_path, *host_command(f"tcp/127.0.0.1:{free_port()}"))
    host.wait_for(children={WORKER: 1, TRACKER: 1}, words="ready")
    host.assert_ended_cleanly(host.signal_and_wait(signum), signum)
    assert f"received {signal.Signals(signum).name}, shutting down" in host.text()


def test_planner_host_reloads_on_sighup_and_keeps_serving(tmp_path: Path) -> None:
    host = Command(tmp_path, *host_command(f"tcp/127.0.0.1:{free_port()}"))
    host.wait_for(children={WORKER: 1}, words="ready")
    first = {pid for pid, (_, c) in host.tree.items() if WORKER in c}
    host.proc.send_signal(signal.SIGHUP)
    host.wait_for(children={WORKER: 1}, words="now serving echo_planners:EchoController")
    assert host.proc.poll() is None
    assert not first & {pid for pid, (_, c) in process_tree(host.proc.pid).items() if WORKER in c}
    host.assert_ended_cleanly(host.signal_and_wait(signal.SIGTERM), signal.SIGTERM)


def test_a_busy_worker_dies_with_a_killed_host(tmp_path: Path, zsession_factory: Any) -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    no_kill = ("--deadline", "60", "--hang-grace", "60")  # the host would let it sleep on
    host = Command(tmp_path, *host_command(endpoint, "FaultyController", *no_kill))
    host.wait_for(children={WORKER: 1, TRACKER: 1}, words="ready")
    params: dict[str, ParamValue] = {"fault": "sleep", "sleep_s": 60.0}
    client = ControllerClient(
        zsession_factory(endpoint), KEY, make_costmap(), params=params, timeouts=GENEROUS
    )
    assert client.wait_for_host(15)
    client.configure()
    client.activate()
    client.timeouts = Timeouts(call=0.5)
    with pytest.raises(NoValidControl):
        client.compute_velocity_commands(pose(), Twist())  # the worker sleeps in the planner
    assert host.signal_and_wait(signal.SIGKILL) == -signal.SIGKILL
    assert wait_until(lambda: not survivors(host.tree), 10), survivors(host.tree)


@pytest.mark.parametrize("signum", SIGNALS, ids=lambda s: s.name)
def test_router_exits_on_signals(tmp_path: Path, signum: int) -> None:
    router = Command(
        tmp_path,
        *python("nav2_pyif.tools.main", "router", "--listen", f"tcp/127.0.0.1:{free_port()}"),
    )
    router.wait_for(children={}, words="listening on")
    router.assert_ended_cleanly(router.signal_and_wait(signum), signum)


@pytest.mark.parametrize("signum", SIGNALS, ids=lambda s: s.name)
def test_reload_waiting_for_an_answer_exits_on_signals(tmp_path: Path, signum: int) -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    session = open_session(ZenohOptions(listen=[endpoint], use_environment=False))
    held: list[zenoh.Query] = []  # a host that never answers
    queryable = session.declare_queryable("nav2_pyif/sig/FollowPath/admin/reload", held.append)
    token = session.liveliness().declare_token("nav2_pyif/sig/FollowPath/host/mute")
    try:
        reload = Command(
            tmp_path,
            *python("nav2_pyif.tools.main", "reload", "--key", "nav2_pyif/sig/FollowPath"),
            *("--connect", endpoint),
        )
        assert wait_until(lambda: held, 20), reload.text()
        reload.assert_ended_cleanly(reload.signal_and_wait(signum), signum)
    finally:
        token.undeclare()
        queryable.undeclare()
        held.clear()
        session.close()


@pytest.mark.parametrize("signum", SIGNALS, ids=lambda s: s.name)
def test_bench_stops_its_host_and_client_processes(tmp_path: Path, signum: int) -> None:
    bench = Command(
        tmp_path, *python("nav2_pyif_bench.cli", "fleet", "--robots", "1", "--seconds", "30")
    )
    # the host and its worker, one client process, the bench's resource tracker and the host's
    bench.wait_for(children={"nav2_pyif.server.cli": 1, WORKER: 2, TRACKER: 2})
    bench.assert_ended_cleanly(bench.signal_and_wait(signum), signum)
    assert f"stopped by {signal.Signals(signum).name}" in bench.text()
