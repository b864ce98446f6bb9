"""``nav2-pyif eval`` for real: planner hosts over Zenoh on loopback, in parallel processes.
In lockstep the report does not depend on the machine's load: an evaluation run on an idle
machine and again with every core kept busy by child processes gives the same report, less
the compute figures."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
from nav2_pyif.evaluation.report import without_compute

from tests.conftest import nav2_pyif_tool, process_tree, survivors, wait_until

pytestmark = pytest.mark.integration

SMALL_EVAL = ("--controller", "pure_pursuit", "apf", "--generated", "2", "--jobs", "2")
BUSY = "while True:\n    pass\n"


def evaluate(out: Path, *args: str) -> dict[str, Any]:
    done = nav2_pyif_tool("eval", *SMALL_EVAL, "--no-plots", "--out", str(out), *args, timeout=400)
    assert done.returncode == 0, done.stderr
    report: dict[str, Any] = json.loads((out / "eval.json").read_text())
    return report


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of ``pid`` so far, from /proc."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def hosts_under(pid: int) -> int:
    """How many planner hosts run under ``pid`` now (one per run in progress)."""
    return sum("nav2_pyif.server.cli" in cmd for _, cmd in process_tree(pid).values())


@contextmanager
def every_core_busy() -> Iterator[list[subprocess.Popen[bytes]]]:
    """A spinning child process per core, stopped (by its own handle) when the block ends."""
    spinners = [subprocess.Popen([sys.executable, "-c", BUSY]) for _ in range(os.cpu_count() or 1)]
    try:
        yield spinners
    finally:
        for spinner in spinners:
            spinner.kill()
            spinner.wait()


@pytest.mark.timeout(900)  # two evaluations of four runs each, the second on a loaded machine
def test_the_report_is_the_same_on_an_idle_and_a_loaded_machine(tmp_path: Path) -> None:
    idle = evaluate(tmp_path / "idle")
    with every_core_busy() as spinners:
        started = time.monotonic()
        loaded = evaluate(tmp_path / "loaded")
        took = time.monotonic() - started
        burnt = [cpu_seconds(s.pid) for s in spinners]
    # the load was real: each spinner took a good share of a core while the eval ran (a share
    # of its wall time, not a fixed number of seconds: a faster machine ends the eval sooner)
    assert min(burnt) > 0.25 * took, (burnt, took)
    assert [r["planner"] for r in idle["summary"]] == ["pure_pursuit", "apf"]
    assert len(idle["runs"]) == 4
    assert any(r["success"] for r in idle["runs"]), idle["runs"]  # not four failures alike
    assert all(r.get("compute_p99_ms") is not None for r in idle["runs"]), idle["runs"]
    assert without_compute(loaded) == without_compute(idle)
    compared = nav2_pyif_tool("eval", "--compare", str(tmp_path / "idle"), str(tmp_path / "loaded"))
    assert compared.returncode == 0 and "identical: 4 run(s) of 2 planner(s)" in compared.stdout, (
        compared.stdout + compared.stderr
    )


def test_the_outputs_are_written_and_the_table_printed(tmp_path: Path) -> None:
    done = nav2_pyif_tool(
        "eval", "--controller", "pure_pursuit", "--generated", "1", "--jobs", "1",
        "--out", str(tmp_path), timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "1 planner(s) x 1 scenario(s), lockstep" in done.stderr
    header = done.stdout.splitlines()[0].split()
    assert header[:3] == ["planner", "runs", "success"] and "BARN" in header
    assert done.stdout.splitlines()[2].split()[:2] == ["pure_pursuit", "1"]
    csv_lines = (tmp_path / "eval.csv").read_text().splitlines()
    assert csv_lines[0].startswith("planner,runs,successes,success_rate") and len(csv_lines) == 2
    for png in ("eval.png", "scenarios/gen_s0_d10_000.png", "runs/gen_s0_d10_000/pure_pursuit.png"):
        assert (tmp_path / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", png
    assert (tmp_path / "maps" / "gen_s0_d10_000.yaml").is_file()
    host_log = (tmp_path / "runs" / "gen_s0_d10_000" / "pure_pursuit.host.log").read_text()
    assert "now serving" in host_log or "serving nav2_pyif_planners" in host_log, host_log


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (("--map", "no_such_map"), "the bundled maps: office, cluttered"),
        (("--generated", "1", "--density", "1.5"), "--density 1.5: give a fraction in [0, 1)"),
        (("--controller", "apf", "apf"), "a planner is named twice"),
        (("--compare", "no_such_dir", "other"), "--compare: no_such_dir is not a readable"),
    ],
    ids=["unknown-map", "bad-density", "twice", "compare-unreadable"],
)
def test_bad_input_is_a_usage_error(tmp_path: Path, args: tuple[str, ...], said: str) -> None:
    done = nav2_pyif_tool("eval", "--out", str(tmp_path), *args, timeout=60)
    assert done.returncode == 2, done.stderr
    assert said in done.stderr


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_signal_stops_every_run_and_host(tmp_path: Path, signum: int) -> None:
    """Stopped mid-evaluation, eval ends its worker processes and their planner hosts and
    exits 128 + signum. The signal goes to eval alone, as from a process supervisor."""
    eval_ = subprocess.Popen(
        [sys.executable, "-m", "nav2_pyif.tools.main", "eval", *SMALL_EVAL, "--no-plots",
         "--out", str(tmp_path)],
        stderr=subprocess.PIPE,
        text=True,
    )  # fmt: skip
    try:
        assert wait_until(lambda: hosts_under(eval_.pid) == 2, 120), process_tree(eval_.pid)
        tree = process_tree(eval_.pid)
        eval_.send_signal(signum)
        _, err = eval_.communicate(timeout=60)
    finally:
        if eval_.poll() is None:
            eval_.kill()
            eval_.wait()
    assert eval_.returncode == 128 + signum, err
    assert wait_until(lambda: not survivors(tree), 10), survivors(tree)
