"""What a user sees when a planner crashes, exits or hangs: the run still ends with its report,
PNG and JSON (and the host's log beside them), showing the planner's own line; a standalone
host logs the same stack. Real processes throughout: ``nav2-pyif sim`` and ``planner-host``."""

from __future__ import annotations

import contextlib
import json
import os
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif import ControllerException, Plan
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.testing import drive

from tests.conftest import FIXTURES, free_port, host_process, make_costmap, open_client_session
from tests.test_host_e2e import pose
from tests.test_sim import run_sim_command

pytestmark = pytest.mark.integration

SOURCE = FIXTURES / "crashing.py"


def line_of(marker: str) -> int:
    """The line of the fixture planner's crash (marked by a comment) in crashing.py."""
    lines = SOURCE.read_text().splitlines()
    return next(i for i, line in enumerate(lines, 1) if f"# {marker}" in line)


def own_frame(marker: str) -> str:
    """The planner's frame as faulthandler writes it ("... line N in method")."""
    return f'crashing.py", line {line_of(marker)}'


CASES = [
    ("Segfaults", "the crash: SIGSEGV", "killed by signal SIGSEGV during compute_velocity"),
    ("Exits", "the crash: the worker exits", "exited with code 3 during compute_velocity"),
    ("Hangs", "the hang: never returns", "overran its 1 s deadline"),
]


@pytest.mark.parametrize(("planner", "marker", "cause"), CASES)
def test_sim_reports_a_crashed_or_hung_planner_with_its_own_line(
    tmp_path: Path, planner: str, marker: str, cause: str
) -> None:
    # A hang in lockstep is waited for up to --lockstep-limit (60 s) before the host's deadline
    # answers; real time shows the robot's rule: the host's 1 s deadline, calls failing meanwhile.
    clock = ["--realtime", "--call-timeout", "0.25"] if planner == "Hangs" else []
    result = run_sim_command(tmp_path, "--controller", f"crashing:{planner}", *clock)
    said = result.stdout + result.stderr
    assert result.returncode == 1, said
    assert "NOT REACHED: controller failed: " in result.stdout, said
    assert cause in result.stdout, said
    # the planner's own line, in the report (first) and in the JSON record
    report = result.stdout.split("NOT REACHED")[0]
    assert own_frame(marker) in report, said
    stem = tmp_path / f"office_crashing.{planner}"
    record = json.loads(Path(f"{stem}.json").read_text())
    assert own_frame(marker) in record["traceback"]
    assert not record["summary"]["reached"]
    assert Path(f"{stem}.png").stat().st_size > 10_000
    # the host's log, kept beside them, has the stack too
    host_log = Path(f"{stem}.host.log").read_text()
    assert own_frame(marker) in host_log
    assert f"{stem}.host.log" in result.stdout


def test_a_planners_print_and_logger_lines_are_shown_marked(tmp_path: Path) -> None:
    result = run_sim_command(tmp_path, "--controller", "crashing:Segfaults")
    lines = result.stderr.splitlines()
    printed = "[nav2_pyif/sim/FollowPath] Segfaults: about to read address 0"
    assert printed in lines, result.stderr
    logged = [line for line in lines if "Segfaults: cycle at x=" in line]
    assert logged and "[INFO]" in logged[0], result.stderr
    assert "[nav2_pyif.planner.FollowPath]" in logged[0]
    # the host's own lines stay in its log
    assert "session" not in result.stderr and "serving" not in result.stderr


@contextlib.contextmanager
def served(
    tmp_path: Path, planner: str, *flags: str
) -> Iterator[tuple[PlannerHostProcess, ControllerClient]]:
    """A standalone planner-host serving crashing.py's ``planner``, and a client of it past
    configure and activate."""
    key = "nav2_pyif/reports/FollowPath"
    args = ["--serve", f"{key}=crashing:{planner}", *flags]
    host = host_process(free_port(), args, tmp_path / "host.log").start()
    session = open_client_session(host.endpoint)
    timeouts = Timeouts(call=3.0, configure=30.0)
    client = ControllerClient(session, key, make_costmap(), timeouts=timeouts)
    try:
        assert client.wait_for_host(30), host.log()
        client.configure()
        client.activate()
        yield host, client
    finally:
        client.close()
        session.close()
        host.close()


@pytest.mark.parametrize(("planner", "marker", "cause"), CASES)
def test_a_standalone_host_logs_the_planners_stack(
    tmp_path: Path, planner: str, marker: str, cause: str
) -> None:
    with served(tmp_path, planner, "--deadline", "1", "--hang-grace", "1") as (host, client):
        client.set_plan(Plan(np.zeros((3, 3)), "odom"))
        with pytest.raises(ControllerException) as info:
            client.compute_velocity_commands(pose(), Twist())
        assert own_frame(marker) in info.value.remote_traceback  # the error carries it
        deadline = time.monotonic() + 20
        while own_frame(marker) not in host.log():
            assert time.monotonic() < deadline, host.log()
            time.sleep(0.1)
        assert cause in host.log()


@pytest.mark.parametrize(
    ("planner", "marker", "words"),
    [
        ("ReturnsNan", "the bad return: NaN", "returned a non-finite velocity: linear.x=nan"),
        ("ReturnsNone", "the bad return: none at all", "returned NoneType"),
        ("ReturnsTuple", "the bad return: a tuple", "returned tuple"),
    ],
)
def test_a_refused_return_value_points_at_the_planners_return_line(
    tmp_path: Path, planner: str, marker: str, words: str
) -> None:
    with served(tmp_path, planner) as (_, client):
        with pytest.raises(ControllerException, match=words) as info:
            client.compute_velocity_commands(pose(), Twist())
        tb = info.value.remote_traceback.splitlines()
        assert tb[0] == "Traceback (most recent call last):", tb
        assert tb[1].endswith(f"{own_frame(marker)}, in compute_velocity_commands")
        text = "\n".join(tb)
        assert "runtime.py" not in text and "results.py" not in text  # none of the host's


def test_drive_shows_the_planners_own_lines_and_keeps_the_hosts_log(
    capfd: pytest.CaptureFixture[str],
) -> None:
    result = drive("crashing:Segfaults", path=[str(FIXTURES)], timeout=5.0)
    err = capfd.readouterr().err
    assert "[nav2_pyif/sim/FollowPath] Segfaults: about to read address 0" in err
    assert "[nav2_pyif.planner.FollowPath] Segfaults: cycle at x=" in err
    assert not result.reached and "SIGSEGV" in result.outcome
    assert own_frame("the crash: SIGSEGV") in result.traceback
    assert own_frame("the crash: SIGSEGV") in result.host_log


def test_the_stack_files_have_no_name_once_the_workers_are_serving(tmp_path: Path) -> None:
    # A host killed with SIGKILL cannot remove them: they must already be gone from /tmp.
    with served(tmp_path, "Segfaults") as (host, _):
        assert host.proc is not None
        fds = Path(f"/proc/{host.proc.pid}/fd")
        links = [os.readlink(fd) for fd in fds.iterdir() if fd.is_symlink()]
        stacks = [link for link in links if "nav2_pyif_worker_" in link]
        assert stacks and all(link.endswith(" (deleted)") for link in stacks), links
