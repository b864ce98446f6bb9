"""Runs testenv/build.sh into a temporary prefix, for the tests of its steps."""

from __future__ import annotations

import subprocess
from pathlib import Path

BUILD = Path(__file__).resolve().parents[1] / "testenv" / "build.sh"


def run_build(tmp_path: Path, *args: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    """build.sh ARGS with its prefix at tmp_path/prefix and its sources at tmp_path/src."""
    return subprocess.run(
        [
            "bash",
            str(BUILD),
            *("--prefix", str(tmp_path / "prefix"), "--sources", str(tmp_path / "src")),
            *args,
        ],
        capture_output=True,
        text=True,
        timeout=timeout,
    )
