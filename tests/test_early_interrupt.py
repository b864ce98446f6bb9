"""Ctrl-C at any moment of a command's start ends it as a later one does: exit code 130, one
line, no KeyboardInterrupt traceback. The commands are started for real in their own process
group and SIGINT is sent to that group, as a terminal's Ctrl-C is: during ./scripts/sim.sh's
bootstrap, while the interpreter starts and while the command imports NumPy, rclpy and Zenoh
(about half a second, where Python's default handler used to answer with a traceback and 1)."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import ENV_SCRIPT, ROOT, in_project_env

pytestmark = pytest.mark.integration

SIGINT_EXIT = 128 + signal.SIGINT
#: What a shell reports as 130: that exit code, or death by SIGINT's default action (a signal
#: that lands before bash has set its trap, or before the interpreter starts).
ENDED_BY_SIGINT = (SIGINT_EXIT, -signal.SIGINT)


def _as_from_a_terminal() -> None:
    """In the child before exec: SIGINT's default action, as a terminal's shell starts a
    command with. A suite started in the background by a shell without job control inherits
    SIGINT ignored, and an ignored SIGINT would never reach the command."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def interrupted(argv: list[str], delay: float, cwd: Path, **popen: object) -> tuple[int, str]:
    """Start ``argv`` in its own process group, SIGINT the group after ``delay`` seconds;
    (exit code, output)."""
    popen.setdefault("preexec_fn", _as_from_a_terminal)
    proc = subprocess.Popen(
        argv,
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
        **popen,  # type: ignore[call-overload]
    )
    time.sleep(delay)
    os.killpg(proc.pid, signal.SIGINT)
    try:
        output, _ = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        output, _ = proc.communicate()
        pytest.fail(f"{argv} still running 60 s after SIGINT:\n{output}")
    return proc.returncode, output


@pytest.mark.timeout(300)
def test_ctrl_c_in_the_first_second_of_sim_sh_exits_130_without_a_traceback(
    tmp_path: Path,
) -> None:
    env = dict(os.environ, NAV2_PYIF_VENV=str(ENV_SCRIPT.parent))
    # From the bootstrap's checks (0-0.4 s here) through Python's start and the imports.
    for delay in (0.0, 0.15, 0.3, 0.45, 0.6, 0.9):
        code, output = interrupted([str(ROOT / "scripts" / "sim.sh")], delay, tmp_path, env=env)
        assert code in ENDED_BY_SIGINT, f"SIGINT after {delay} s: exit {code}:\n{output}"
        assert "Traceback" not in output, f"SIGINT after {delay} s:\n{output}"


def _held_back() -> None:
    """In the child before exec: SIGINT blocked, so it is pending when the command starts,
    whatever the machine's speed (the case of a Ctrl-C during the interpreter's start)."""
    _as_from_a_terminal()
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})


@pytest.mark.parametrize(
    "command", ["nav2-pyif sim", "planner-host --key nav2_pyif/t/FollowPath --planner m:C"]
)
def test_sigint_before_a_command_can_handle_it_exits_130_without_a_traceback(
    tmp_path: Path, command: str
) -> None:
    code, output = interrupted(
        in_project_env(f"exec {command}"), 0.0, tmp_path, preexec_fn=_held_back
    )
    assert code == SIGINT_EXIT, output
    assert "Traceback" not in output and "stopped by SIGINT" in output, output


def test_sigint_while_the_command_imports_exits_130_without_a_traceback(tmp_path: Path) -> None:
    # 0.3 s: after the interpreter's start (about 0.05 s), within the imports (about 0.7 s).
    code, output = interrupted(in_project_env("exec nav2-pyif sim"), 0.3, tmp_path)
    assert code == SIGINT_EXIT, output
    assert "Traceback" not in output, output
