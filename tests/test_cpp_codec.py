"""The C++ codec (bridge_plugin/) against the shared vectors: configure, build and run its
GoogleTest suite with ctest. Skipped, naming what is missing, on machines without the C++
toolchain or the codec's Debian packages (libmsgpack-dev: msgpack-c, libgtest-dev,
nlohmann-json3-dev, zlib1g-dev).

The build directory (build/cpp_codec, git-ignored) is kept between runs, so only the first run
compiles everything (~1 minute on 2 cores).
"""

from __future__ import annotations

import fcntl
import os
import re
import shutil
import subprocess
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

import pytest

pytestmark = pytest.mark.cpp

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "bridge_plugin"
BUILD = ROOT / "build" / "cpp_codec"
VECTORS = ROOT / "protocol" / "vectors"

# What the build needs, as (what to report, header that proves it is installed).
HEADERS = [
    ("msgpack-c (apt: libmsgpack-dev; rosdep key msgpack)", "msgpack.h"),
    ("GoogleTest (apt: libgtest-dev)", "gtest/gtest.h"),
    ("nlohmann-json (apt: nlohmann-json3-dev)", "nlohmann/json.hpp"),
    ("zlib (apt: zlib1g-dev)", "zlib.h"),
]


def _include_dirs() -> list[Path]:
    dirs = [Path("/usr/include"), Path("/usr/local/include")]
    for var in ("CPATH", "CPLUS_INCLUDE_PATH"):
        dirs += [Path(p) for p in os.environ.get(var, "").split(os.pathsep) if p]
    return dirs


def _missing() -> list[str]:
    missing = []
    if shutil.which("cmake") is None:
        missing.append("cmake")
    compilers = [os.environ.get("CXX", ""), "c++", "g++", "clang++"]
    if not any(c and shutil.which(c) for c in compilers):
        missing.append("a C++ compiler (c++, g++ or clang++)")
    if shutil.which("make") is None and shutil.which("ninja") is None:
        missing.append("make or ninja")
    for what, header in HEADERS:
        if not any((d / header).is_file() for d in _include_dirs()):
            missing.append(what)
    return missing


def _run(
    args: list[str], timeout: float, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        args, cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout, check=False
    )


def _tail(result: subprocess.CompletedProcess[str], lines: int = 60) -> str:
    text = (result.stdout + result.stderr).splitlines()
    return "\n".join(text[-lines:])


@contextmanager
def built_tree(
    tree: Path, options: list[str], targets: Sequence[str] = (), timeout: float = 540
) -> Iterator[Path]:
    """Configures the codec-only CMake tree `tree` (warnings as errors, the shared vectors)
    with `options` and builds `targets` (all when none), failing the test on an error; the
    tree is the caller's alone until the block ends."""
    tree.mkdir(parents=True, exist_ok=True)
    # One build at a time in a shared tree (parallel pytest runs, two checkouts' CI).
    with open(tree / ".pytest.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        configure = _run(
            [
                "cmake",
                "-S",
                str(SOURCE),
                "-B",
                str(tree),
                "-DNAV2_PYIF_CODEC_ONLY=ON",
                "-DNAV2_PYIF_WARNINGS_AS_ERRORS=ON",
                f"-DNAV2_PYIF_VECTORS_DIR={VECTORS}",
                *options,
            ],
            timeout=120,
        )
        assert configure.returncode == 0, "cmake configure failed:\n" + _tail(configure)
        target_args = ["--target", *targets] if targets else []
        build = _run(["cmake", "--build", str(tree), "-j2", *target_args], timeout=timeout)
        assert build.returncode == 0, f"C++ build in {tree} failed:\n" + _tail(build)
        yield tree


@pytest.fixture(scope="module")
def build_dir() -> Iterator[Path]:
    missing = _missing()
    if missing:
        pytest.skip("C++ codec tests need: " + ", ".join(missing))
    with built_tree(BUILD, []) as tree:
        yield tree


@pytest.mark.timeout(600)  # the first build compiles GoogleTest-heavy sources on 2 cores
def test_cpp_codec_passes_its_googletest_suite(build_dir: Path) -> None:
    result = _run(
        ["ctest", "--test-dir", str(build_dir), "--output-on-failure", "-j2"], timeout=300
    )
    assert result.returncode == 0, "C++ codec tests failed:\n" + _tail(result, 200)
    summary = re.search(r"(\d+)% tests passed, (\d+) tests failed out of (\d+)", result.stdout)
    assert summary, "no ctest summary:\n" + _tail(result)
    total = int(summary.group(3))
    # Every vector is one test case; fewer tests than vectors means some were not registered.
    vectors = len(list(VECTORS.glob("*.msgpack")))
    assert int(summary.group(2)) == 0
    assert total > vectors, f"only {total} C++ tests for {vectors} vectors"
