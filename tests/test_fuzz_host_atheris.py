"""The coverage-guided fuzzer of the host's request path (tests/fuzz_host_path.py, atheris)
runs a short, fixed number of inputs in the suite: every seed and some of their mutations,
with no crash. Its campaigns (minutes) are reported in RELIABILITY.md."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]
RUNS = 600


@pytest.mark.skipif(
    importlib.util.find_spec("atheris") is None,
    reason="atheris is not installed (the dev extra installs it on x86-64 Linux)",
)
def test_a_short_fuzzing_run_finds_no_crash(tmp_path: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "tests.fuzz_host_path", "--runs", str(RUNS),
         "--artifacts", str(tmp_path)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
    )  # fmt: skip
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-4000:]
    assert f"Done {RUNS} runs" in output, output[-4000:]
    assert not list(tmp_path.iterdir()), "libFuzzer saved a crashing input"
    coverage = re.findall(r"cov: (\d+)", output)
    # the host's modules instrumented (about 500 edges from the seeds alone), not only a few
    assert coverage and int(coverage[-1]) > 400, f"coverage: {coverage[-1:]}"


def test_the_fuzzer_refuses_a_bad_option() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "tests.fuzz_host_path", "--seconds", "-3"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2
    assert "argument --seconds:" in done.stderr and "'-3'" in done.stderr
