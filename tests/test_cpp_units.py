"""The C++ plugin's logic (bridge_plugin/src/client: session, epoch and seq, state re-sent
after a host restart, fail fast, timeouts, costmap versions, error mapping, settings, the local
planner host's start and stop), run by ctest on fakes, without Nav2 or Zenoh. Built by the same
codec-only CMake tree as tests/test_cpp_codec.py (its ``build_dir`` fixture), labelled
``client``; skipped with that test's reasons on machines without the C++ toolchain.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.test_cpp_codec import _run, _tail, build_dir  # noqa: F401  (the shared fixture)

pytestmark = pytest.mark.cpp

# Each C++ twin of a tests/test_host_e2e.py scenario must have run, and the replay of each
# shared session transcript (protocol/vectors/transcripts; tests/test_transcripts.py replays
# them in Python): fail-over to a replica is one of those, its hand-written twin gone.
TRANSCRIPTS = Path(__file__).resolve().parents[1] / "protocol" / "vectors" / "transcripts"
MIRRORED = [
    "ControllerSessionTest.FullSession",
    "ControllerSessionTest.CostmapTravelsOnlyWhenChanged",
    "ControllerSessionTest.HostRestartMidSessionRestoresThePlan",
    "ControllerSessionTest.NoHostFailsFast",
    "ControllerSessionTest.AHungCallTimesOutAndTheNextCallWorks",
    "ControllerSessionTest.AReplyOfAnotherSeqIsAnError",
    "ControllerSessionTest.ErrorsCrossTheWireTyped",
    "PlannerSessionTest.CancellationIsForwardedOnceAndThePlannerAnswers",
]
MIRRORED += [
    f"Transcripts/TranscriptTest.ReplaysByteForByte/{p.stem}" for p in TRANSCRIPTS.glob("*.json")
]
# and the replay of the key rules (protocol/vectors/keys.json, written by keys.py)
MIRRORED += [
    "KeysVector.EveryKeyUnderAPrefixIsThePythonKeySpaces",
    "KeysVector.APrefixIsRefusedWithThePythonMessageOrAccepted",
]


@pytest.mark.timeout(600)
def test_cpp_plugin_units_pass(build_dir: Path) -> None:  # noqa: F811
    listed = _run(["ctest", "--test-dir", str(build_dir), "-L", "client", "-N"], timeout=120)
    assert listed.returncode == 0, _tail(listed)
    for name in MIRRORED:
        assert name in listed.stdout, f"{name} is not registered:\n" + _tail(listed)
    result = _run(
        ["ctest", "--test-dir", str(build_dir), "-L", "client", "--output-on-failure", "-j2"],
        timeout=300,
    )
    assert result.returncode == 0, "C++ plugin unit tests failed:\n" + _tail(result, 200)
    summary = re.search(r"(\d+)% tests passed, (\d+) tests failed out of (\d+)", result.stdout)
    assert summary, "no ctest summary:\n" + _tail(result)
    assert int(summary.group(2)) == 0
    assert int(summary.group(3)) >= 50, "fewer C++ unit tests than expected:\n" + _tail(result)
