"""``planner-host --respawn`` (nav2_pyif.server.respawn): the keeper the Nav2 plugin starts as
its local host restarts the host with a back-off, and leaves no process behind, on real
processes (a shell stands in for the host; one test runs the real command)."""

from __future__ import annotations

import contextlib
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import process_tree, survivors, wait_until
from tests.test_signals import Command

pytestmark = pytest.mark.integration

#: The keeper of nav2_pyif.server.respawn.keep: its timings (JSON), the parent it ends with
#: (0: none) and the command it keeps.
KEEPER = (
    "import json, logging, sys; from nav2_pyif.server.respawn import keep; "
    "logging.basicConfig(level='INFO', format='%(message)s'); "
    "sys.exit(keep(sys.argv[3:], parent=int(sys.argv[2]) or None, **json.loads(sys.argv[1])))"
)
FAST = {"first_delay": 0.1, "max_delay": 0.4, "stable_after": 1.0, "grace": 0.5}


def keeper_argv(script: str, parent: str = "0", **timings: float) -> list[str]:
    """The command line of a keeper of ``sh -c script``, with FAST's timings or these, ending
    with ``parent`` (a pid, or "0")."""
    return [
        sys.executable,
        "-c",
        KEEPER,
        json.dumps({**FAST, **timings}),
        parent,
        "sh",
        "-c",
        script,
    ]


def keeper(tmp_path: Path, script: str, **timings: float) -> Command:
    """A keeper of ``sh -c script`` run in ``tmp_path``."""
    return Command(tmp_path, *keeper_argv(f"cd {tmp_path}; {script}", "0", **timings))


def delays(text: str) -> list[str]:
    return re.findall(r"; restarting in ([0-9.]+) s", text)


def host_pid(tmp_path: Path, keeper: Command) -> int:
    """The pid the kept shell wrote to ``pid`` (once it has)."""
    pid_file = tmp_path / "pid"
    assert wait_until(lambda: pid_file.exists() and pid_file.read_text().endswith("\n"), 10), (
        keeper.text()
    )
    return int(pid_file.read_text())


@pytest.mark.parametrize(
    ("ending", "said"),
    [("exit 3", "exited with status 3"), ("kill -KILL $$", "killed by signal 9 (SIGKILL)")],
)
def test_a_host_that_ends_is_started_again(tmp_path: Path, ending: str, said: str) -> None:
    starts = tmp_path / "starts"
    kept = keeper(tmp_path, f"echo $$ >> starts; {ending}")
    assert wait_until(lambda: starts.exists() and len(starts.read_text().split()) >= 3, 10)
    kept.assert_ended_cleanly(kept.signal_and_wait(signal.SIGTERM), signal.SIGTERM)
    first = starts.read_text().split()[0]
    assert f"planner host (pid {first}) {said}; restarting in 0.1 s" in kept.text()


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_ends_the_keeper_and_its_host(tmp_path: Path, signum: int) -> None:
    kept = keeper(tmp_path, "echo $$ > pid; exec sleep 60", grace=5.0)
    host = host_pid(tmp_path, kept)
    assert host in process_tree(kept.proc.pid)
    began = time.monotonic()
    kept.assert_ended_cleanly(kept.signal_and_wait(signum), signum)
    assert time.monotonic() - began < 4  # SIGTERM did it: no SIGKILL after the grace
    assert "restarting" not in kept.text()  # stopping is no reason to restart


def test_a_host_ignoring_sigterm_is_killed_after_the_grace(tmp_path: Path) -> None:
    kept = keeper(tmp_path, "trap '' TERM; echo $$ > pid; while :; do sleep 0.05; done")
    host = host_pid(tmp_path, kept)
    kept.assert_ended_cleanly(kept.signal_and_wait(signal.SIGTERM), signal.SIGTERM)
    assert f"planner host (pid {host}) ignored SIGTERM; killing it" in kept.text()


def test_a_killed_keeper_leaves_no_host(tmp_path: Path) -> None:
    kept = keeper(tmp_path, "echo $$ > pid; exec sleep 60")
    host = host_pid(tmp_path, kept)
    tree = process_tree(kept.proc.pid)
    assert host in tree
    kept.proc.kill()
    kept.proc.wait(10)
    assert wait_until(lambda: not survivors(tree), 10), survivors(tree)


def test_a_keeper_ends_with_the_plugin_that_started_it(tmp_path: Path) -> None:
    """The Nav2 plugin names itself (planner-host --parent-pid): a killed Nav2 (here a shell
    killed with SIGKILL, which can clean nothing up) leaves neither keeper nor host."""
    kept = keeper_argv("echo $$ > pid; exec sleep 60", parent="$$")
    command = " ".join(arg if arg == "$$" else shlex.quote(arg) for arg in kept)
    starter = Command(tmp_path, "sh", "-c", f"cd {tmp_path}; {command} & wait")
    try:
        host = host_pid(tmp_path, starter)
        tree = process_tree(starter.proc.pid)
        assert host in tree and len(tree) == 2, tree  # the keeper and the host
        starter.proc.kill()
        starter.proc.wait(10)
        assert wait_until(lambda: not survivors(tree), 10), survivors(tree)
    finally:  # whatever a failure left: the starter's group holds the keeper and the host
        with contextlib.suppress(ProcessLookupError):
            os.killpg(starter.proc.pid, signal.SIGKILL)
        starter.proc.wait(10)


def test_a_keeper_whose_plugin_is_gone_already_starts_nothing(tmp_path: Path) -> None:
    gone = subprocess.Popen(["true"])  # a process id that no longer runs
    gone.wait()
    (tmp_path / "orphan").mkdir()
    orphan = Command(
        tmp_path / "orphan",
        *keeper_argv(  # not this keeper's parent: gone
            f"cd {tmp_path / 'orphan'}; echo started > started; exec sleep 60", str(gone.pid)
        ),
    )
    assert orphan.proc.wait(10) == 1, orphan.text()
    assert not (tmp_path / "orphan" / "started").exists()


def test_the_back_off_doubles_to_its_bound_and_resets_after_a_stable_run(tmp_path: Path) -> None:
    (tmp_path / "runs").touch()
    # runs 1 to 4 end at once, every later one after 1.2 s (stable: 1 s)
    script = 'n=$(wc -l < runs); echo >> runs; [ "$n" -ge 4 ] && sleep 1.2; exit 3'
    kept = keeper(tmp_path, script)
    assert wait_until(lambda: len(delays(kept.text())) >= 6, 20), kept.text()
    kept.assert_ended_cleanly(kept.signal_and_wait(signal.SIGTERM), signal.SIGTERM)
    assert delays(kept.text())[:6] == ["0.1", "0.2", "0.4", "0.4", "0.1", "0.1"], kept.text()


@pytest.mark.parametrize("how", ["--respawn", "NAV2_PYIF_RESPAWN=1"])
def test_planner_host_respawn_keeps_a_host_without_respawn(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, how: str
) -> None:
    """The real command: its child is planner-host without --respawn (else it would keep a
    keeper, never exiting), here one that cannot load its planner, exit status 2."""
    flags = [how] if how.startswith("--") else []
    if not flags:
        monkeypatch.setenv(*how.split("="))
    command = [sys.executable, "-m", "nav2_pyif.server.cli", *flags]
    kept = Command(tmp_path, *command, "--key", "nav2_pyif/t/k", "--planner", "no_such_m:C")
    assert wait_until(lambda: len(delays(kept.text())) >= 2, 30), kept.text()
    kept.assert_ended_cleanly(kept.signal_and_wait(signal.SIGTERM), signal.SIGTERM)
    text = kept.text()
    assert delays(text)[:2] == ["1.0", "2.0"], text
    assert "exited with status 2; restarting in 1.0 s" in text
    started = re.findall(r"planner host started \(pid \d+\): (.*)", text)
    assert started and all("--res" not in line for line in started), started


@pytest.mark.parametrize("how", ["--parent-pid", "NAV2_PYIF_PARENT_PID"])
def test_planner_host_respawn_whose_parent_is_gone_starts_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, how: str
) -> None:
    """The real command binds its keeper to the process it is given (the Nav2 plugin passes
    --parent-pid; the environment variable works too): that process gone, it exits at once."""
    gone = subprocess.Popen(["true"])
    gone.wait()
    flags = [how, str(gone.pid)] if how.startswith("--") else []
    if not flags:
        monkeypatch.setenv(how, str(gone.pid))
    command = [sys.executable, "-m", "nav2_pyif.server.cli", "--respawn", *flags]
    kept = Command(tmp_path, *command, "--key", "nav2_pyif/t/k", "--planner", "no_such_m:C")
    assert kept.proc.wait(30) == 1, kept.text()
    assert "planner host started" not in kept.text()
