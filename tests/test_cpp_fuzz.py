"""The C++ decoders under libFuzzer (bridge_plugin/fuzz, fuzz/README.md): each harness, built
with clang, AddressSanitizer and UndefinedBehaviorSanitizer, fuzzes for a short fixed time from
the shared vectors, and must end without a crash, a sanitizer report or a broken property; each
input kept under bridge_plugin/fuzz/regressions (a crash found once) must run clean.

Runs through scripts/fuzz_campaign.sh, the command of the long campaigns (RELIABILITY.md), so
its figures are the ones checked here. Skipped, naming what is missing, without clang or
Debian's libclang-rt-14-dev (scripts/test.sh installs both) or the codec's msgpack-c.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.test_cpp_codec import _include_dirs, _run
from tests.test_early_interrupt import _as_from_a_terminal

pytestmark = pytest.mark.cpp

ROOT = Path(__file__).resolve().parents[1]
CAMPAIGN = ROOT / "scripts" / "fuzz_campaign.sh"
BUILD = ROOT / "build" / "cpp_fuzz"
REGRESSIONS = ROOT / "bridge_plugin" / "fuzz" / "regressions"
HARNESSES = ["request", "reply", "structure", "utf8", "params", "keys"]
SECONDS = 10


def _clang() -> str | None:
    for name in (os.environ.get("NAV2_PYIF_FUZZ_CXX", ""), "clang++-14", "clang++"):
        if name and shutil.which(name):
            return name
    return None


def _missing() -> list[str]:
    missing = [] if shutil.which("cmake") else ["cmake"]
    clang = _clang()
    if clang is None:
        missing.append("clang++ (apt: clang-14)")
    else:
        runtime = subprocess.run(
            [clang, "-print-file-name=libclang_rt.fuzzer-x86_64.a"],
            capture_output=True,
            text=True,
            check=False,
        ).stdout.strip()
        if not Path(runtime).is_file():
            # clang 14 prints the bare name when the runtime is not where it looks
            resource = subprocess.run(
                [clang, "-print-runtime-dir"], capture_output=True, text=True, check=False
            ).stdout.strip()
            if not list(Path(resource or "/nonexistent").glob("libclang_rt.fuzzer*.a")):
                missing.append("libFuzzer (apt: libclang-rt-14-dev)")
    if not any((d / "msgpack.h").is_file() for d in _include_dirs()):
        missing.append("msgpack-c (apt: libmsgpack-dev)")
    return missing


@pytest.fixture(scope="module")
def fuzz_env() -> dict[str, str]:
    missing = _missing()
    if missing:
        pytest.skip("C++ fuzzing needs: " + ", ".join(missing))
    env = dict(os.environ)
    env["NAV2_PYIF_FUZZ_CXX"] = _clang() or ""
    return env


def _campaign(
    env: dict[str, str], harness: str, tmp: Path
) -> tuple[subprocess.CompletedProcess[str], dict[str, object]]:
    stats = tmp / "stats.json"
    paths = ["--corpus", str(tmp / "corpus"), "--crashes", str(tmp / "crashes")]
    command = [str(CAMPAIGN), *paths, "--stats", str(stats), harness, str(SECONDS)]
    result = _run(command, timeout=900, env=env)
    figures = json.loads(stats.read_text()) if stats.is_file() else {}
    return result, figures


@pytest.mark.timeout(900)  # the first harness builds the codec with ASan on 2 cores
@pytest.mark.parametrize("harness", HARNESSES)
def test_fuzzing_finds_no_crash(fuzz_env: dict[str, str], harness: str, tmp_path: Path) -> None:
    result, figures = _campaign(fuzz_env, harness, tmp_path)
    output = result.stdout + result.stderr
    assert result.returncode == 0, f"fuzz_{harness} failed:\n{output[-6000:]}"
    assert figures["result"] == "clean" and figures["crashes"] == 0, figures
    # It really ran: the seeds (protocol/vectors, ~150 distinct), then mutations (tens of
    # thousands on an idle machine, a handful on a busy one: the fuzzer is niced), with
    # coverage from the instrumented codec.
    assert int(str(figures["executions"])) > 100, figures
    assert int(str(figures["cov"])) > 20, figures
    assert int(str(figures["corpus_units"])) > 0, figures


@pytest.mark.timeout(900)
def test_each_regression_input_runs_clean(fuzz_env: dict[str, str]) -> None:
    kept = {h: sorted(p for p in (REGRESSIONS / h).glob("*") if p.is_file()) for h in HARNESSES}
    if not any(kept.values()):
        pytest.skip(f"no inputs under {REGRESSIONS.relative_to(ROOT)} (no crash found yet)")
    for harness, inputs in kept.items():
        if not inputs:
            continue
        built = _run([str(CAMPAIGN), "--build-only", harness], timeout=900, env=fuzz_env)
        assert built.returncode == 0, built.stderr[-6000:]
        # libFuzzer given files runs each once and exits: a crash, a report or a broken
        # property makes it fail.
        result = _run([built.stdout.strip(), *map(str, inputs)], timeout=300)
        output = result.stdout + result.stderr
        assert result.returncode == 0, f"fuzz_{harness}:\n{output[-6000:]}"
        assert output.count("Executed ") == len(inputs), output[-3000:]


def _child_running(parent: int, name: str) -> int | None:
    """The pid of `parent`'s child process whose command line names `name`, or None."""
    children = Path(f"/proc/{parent}/task/{parent}/children")
    for pid in children.read_text().split() if children.is_file() else []:
        with contextlib.suppress(OSError):
            if name in Path(f"/proc/{pid}/cmdline").read_text():
                return int(pid)
    return None


@pytest.mark.timeout(900)
@pytest.mark.parametrize(("sig", "code"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_an_interrupted_campaign_ends_its_fuzzer_and_keeps_its_figures(
    fuzz_env: dict[str, str], sig: signal.Signals, code: int, tmp_path: Path
) -> None:
    built = _run([str(CAMPAIGN), "--build-only", "utf8"], timeout=900, env=fuzz_env)
    assert built.returncode == 0, built.stderr[-6000:]
    stats = tmp_path / "stats.json"
    paths = ["--corpus", str(tmp_path / "corpus"), "--crashes", str(tmp_path / "crashes")]
    campaign = subprocess.Popen(
        [str(CAMPAIGN), *paths, "--stats", str(stats), "utf8", "600"],
        cwd=ROOT,
        env=fuzz_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_as_from_a_terminal,  # SIGINT as a terminal's Ctrl-C delivers it
    )
    try:
        deadline = time.monotonic() + 120
        fuzzer = None
        corpus = tmp_path / "corpus"
        # Fuzzing: the fuzzer runs and has added its first inputs to the corpus.
        while time.monotonic() < deadline and not (fuzzer and any(corpus.iterdir())):
            time.sleep(0.2)
            fuzzer = _child_running(campaign.pid, "cpp_fuzz/fuzz_utf8")
        assert fuzzer is not None, "the campaign never started fuzz_utf8"
        campaign.send_signal(sig)
        _, err = campaign.communicate(timeout=60)
    finally:
        campaign.kill()
        campaign.wait()
    assert campaign.returncode == code, err
    assert not Path(f"/proc/{fuzzer}").exists(), "the fuzzer outlived its campaign"
    figures = json.loads(stats.read_text())
    assert figures["result"] == "interrupted", figures
    assert int(str(figures["executions"])) > 0, figures
