"""The C++ unit tests (tests/test_cpp_codec.py, tests/test_cpp_units.py) again under the
sanitizers: AddressSanitizer with UndefinedBehaviorSanitizer on every codec and client test,
and ThreadSanitizer on the client tests, where the carried cycle, the host watcher and the
fake transport's callbacks run on threads of their own. Any report fails the test case that
made it (halt_on_error, a non-zero exit code).

Each build is a tree of its own under build/ (kept between runs) made with the project's
NAV2_PYIF_SANITIZE option (bridge_plugin/cmake/Nav2PyifSanitize.cmake). Skipped, naming what
is missing, without the C++ toolchain and packages of tests/test_cpp_codec.py, or without the
compiler's sanitizer runtime (Debian: libasan8, libubsan1, libtsan2, installed with g++).
"""

from __future__ import annotations

import os
import re
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.test_cpp_codec import _missing, _run, built_tree

pytestmark = pytest.mark.cpp

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "bridge_plugin"
VECTORS = ROOT / "protocol" / "vectors"

# A report ends the program at once with this status, whatever the sanitizer's own default.
REPORT_EXIT = 66
RUNTIME_OPTIONS = {
    "ASAN_OPTIONS": f"halt_on_error=1:detect_leaks=1:exitcode={REPORT_EXIT}",
    "UBSAN_OPTIONS": f"halt_on_error=1:print_stacktrace=1:exitcode={REPORT_EXIT}",
    "TSAN_OPTIONS": f"halt_on_error=1:second_deadlock_stack=1:exitcode={REPORT_EXIT}",
}
REPORT = re.compile(
    r"ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error:|"
    r"WARNING: ThreadSanitizer"
)


@dataclass(frozen=True)
class SanitizedBuild:
    name: str  # build/cpp_<name>
    checks: str  # NAV2_PYIF_SANITIZE
    targets: tuple[str, ...]  # what to build
    label: str  # the ctest label to run; "" for all


BUILDS = [
    SanitizedBuild("asan", "address,undefined", ("test_protocol_codec", "test_client_units"), ""),
    SanitizedBuild("tsan", "thread", ("test_client_units",), "client"),
]


def _sanitizer_missing(checks: str) -> str | None:
    """What keeps the compiler from linking a program with these checks, or None."""
    compiler = os.environ.get("CXX") or "c++"
    with tempfile.TemporaryDirectory() as tmp:
        source = Path(tmp) / "probe.cpp"
        source.write_text("int main() { return 0; }\n")
        probe = subprocess.run(
            [compiler, f"-fsanitize={checks}", str(source), "-o", str(Path(tmp) / "probe")],
            capture_output=True,
            text=True,
            check=False,
        )
    if probe.returncode == 0:
        return None
    return f"{compiler} cannot link -fsanitize={checks} (libasan8/libubsan1/libtsan2)"


@pytest.mark.timeout(1800)  # a first build of GoogleTest-heavy sources, instrumented, on 2 cores
@pytest.mark.parametrize("build", BUILDS, ids=[b.name for b in BUILDS])
def test_cpp_unit_tests_are_sanitizer_clean(build: SanitizedBuild) -> None:
    missing = _missing()
    if missing:
        pytest.skip("C++ sanitizer builds need: " + ", ".join(missing))
    no_runtime = _sanitizer_missing(build.checks)
    if no_runtime:
        pytest.skip(no_runtime)
    # Unoptimised: GoogleTest-heavy sources compile several times faster at -O0, and the
    # sanitizers see more there (nothing inlined or folded away).
    options = [f"-DNAV2_PYIF_SANITIZE={build.checks}", "-DCMAKE_BUILD_TYPE="]
    tree = ROOT / "build" / f"cpp_{build.name}"
    with built_tree(tree, options, build.targets, timeout=1500):
        label = ["-L", build.label] if build.label else []
        env = {**os.environ, **RUNTIME_OPTIONS}
        command = ["ctest", "--test-dir", str(tree), *label, "--output-on-failure", "-j2"]
        result = _run(command, timeout=600, env=env)
    output = result.stdout + result.stderr
    assert result.returncode == 0, f"-fsanitize={build.checks}:\n" + output[-8000:]
    assert not REPORT.search(output), output[-8000:]
    summary = re.search(r"(\d+)% tests passed, (\d+) tests failed out of (\d+)", result.stdout)
    assert summary and int(summary.group(2)) == 0, output[-3000:]
    assert int(summary.group(3)) >= 50, "fewer tests than expected:\n" + output[-3000:]
