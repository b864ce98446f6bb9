"""The benchmark command runs and prints every table BENCHMARKS.md quotes (figures are not
asserted: performance is judged from benchmark runs, not unit tests)."""

from __future__ import annotations

import subprocess
import sys


def test_protocol_benchmark_quick_run_prints_its_tables() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "nav2_pyif_bench.cli", "protocol", "--quick"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    for line in (
        "bare Zenoh get -> empty reply",
        "nav2_pyif cycle, worker process (default)",
        "nav2_pyif cycle, --isolation none",
        "rclpy node over topics",
        "1000-pose plan",
        "400 x 400 costmap",
        "calls/s",
        "machine:",
    ):
        assert line in result.stdout
