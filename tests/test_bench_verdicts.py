"""Benchmark verdicts agree with the figures they print: a ratio printed
"2.00x" against ">= 2x" is MET, whatever digits were not printed, and every printed target
has a verdict (the MPPI one had none)."""

from __future__ import annotations

import re
from typing import Any

import pytest
from nav2_pyif_bench import mppi_bench
from nav2_pyif_bench.cycle_targets import cycle_target_lines
from nav2_pyif_bench.stats import Summary
from nav2_pyif_bench.stats import cycle_target_lines as issue2_target_lines

pytestmark = pytest.mark.unit

FIGURE = re.compile(r"(\d+\.\d+)x.*\(target (<=|>=) (\d+(?:\.\d+)?)x.*\): (MET|NOT MET)")


def assert_verdicts_follow_the_figures(lines: list[str]) -> int:
    """Each ``... 1.23x (target <= 1.5x): MET`` line: the verdict of the figure as printed."""
    judged = 0
    for line in lines:
        found = FIGURE.search(line)
        if found is None:
            continue
        shown, op, target, said = found.groups()
        met = float(shown) <= float(target) if op == "<=" else float(shown) >= float(target)
        assert said == ("MET" if met else "NOT MET"), line
        judged += 1
    return judged


def row(median_us: float, p99_us: float) -> Summary:
    return Summary(n=300, median_us=median_us, p99_us=p99_us, mean_us=median_us)


@pytest.mark.parametrize("ratio", [1.998, 2.004, 1.994, 1.4999, 1.5049, 1.1049])
def test_a_ratio_at_its_target_is_judged_as_printed(ratio: float) -> None:
    worker = row(100.0, 100.0)
    rows = {
        "bare": row(100.0 / ratio, 10.0),
        "pyif": worker,
        "pyif_inproc": row(100.0 / ratio, 10.0),
        "rclcpp": row(100.0 * ratio, 100.0 * ratio),
        "pyif.paced": row(50.0, 50.0 * ratio),
    }
    assert assert_verdicts_follow_the_figures(cycle_target_lines(rows)) == 5
    lines = issue2_target_lines(100.0, 100.0 * ratio, {"worker process": 100.0})
    assert assert_verdicts_follow_the_figures(lines) == 1
    overhead = issue2_target_lines(100.0, 0.0, {"x": 100.0 + 50.04})[0]
    assert "+50.0 µs" in overhead and overhead.endswith(": MET"), overhead


def mppi_row(controller: str, rollouts: int, p99_ms: float) -> dict[str, Any]:
    """One row as mppi_bench.run records it."""
    return {
        "controller": controller,
        "map": "office",
        "rollouts": rollouts,
        "reached": True,
        "cycles": 500,
        "compute_median_ms": p99_ms / 2,
        "compute_p99_ms": p99_ms - 1,
        "round_trip_median_ms": p99_ms / 2 + 1,
        "round_trip_p99_ms": p99_ms,
        "max_rate_hz_at_p99": 1000 / p99_ms,
    }


def test_the_mppi_target_has_a_verdict_per_controller() -> None:
    results = {
        "mppi 1000": mppi_row("mppi", 1000, 49.96),  # printed 50.0 ms: met
        "mppi_jax 1000": mppi_row("mppi_jax", 1000, 5.5),
        "mppi 2000": mppi_row("mppi", 2000, 98.0),
        "mppi_jax 2000": mppi_row("mppi_jax", 2000, 9.8),
        "slow 1000": mppi_row("slow", 1000, 60.0),
    }
    text = mppi_bench.report(results)
    verdicts = [line for line in text.splitlines() if "(target >= 1000 rollouts" in line]
    assert len(verdicts) == 3, text
    mppi, jax, slow = verdicts
    assert "mppi: 1000 rollouts, round trip p99 50.0 ms" in mppi and mppi.endswith(": MET")
    assert "mppi_jax: 2000 rollouts, round trip p99 9.8 ms" in jax and jax.endswith(": MET")
    assert "slow: 1000 rollouts, round trip p99 60.0 ms" in slow and slow.endswith(": NOT MET")


def test_an_mppi_run_below_the_target_batch_is_not_judged_met() -> None:
    text = mppi_bench.report({"mppi 500": mppi_row("mppi", 500, 10.0)})
    assert "mppi: no batch of >= 1000 rollouts" in text and "MET" not in text, text
