"""Latency summaries and the machine description printed with every benchmark."""

from __future__ import annotations

import os
import platform
from dataclasses import dataclass
from importlib import metadata

import numpy as np


@dataclass(frozen=True)
class Summary:
    n: int
    median_us: float
    p99_us: float
    mean_us: float

    @classmethod
    def of_ns(cls, samples_ns: list[int]) -> Summary:
        a = np.asarray(samples_ns, dtype=np.float64) / 1000.0
        return cls(len(a), float(np.median(a)), float(np.percentile(a, 99)), float(a.mean()))

    def row(self, label: str, width: int = 40) -> str:
        return f"  {label:<{width}} {self.median_us:>10.1f} {self.p99_us:>10.1f} {self.n:>7d}"


def header_row(width: int = 40) -> str:
    return f"  {'':<{width}} {'median µs':>10} {'p99 µs':>10} {'n':>7}"


def verdict(value: float, op: str, target: float, digits: int) -> str:
    """MET or NOT MET for ``value`` as printed with ``digits`` decimals: a figure is judged
    as the reader sees it (1.998 printed "2.00x" meets ">= 2x"; no "2.00x: NOT MET")."""
    shown = float(f"{value:.{digits}f}")
    met = shown <= target if op == "<=" else shown >= target
    return "MET" if met else "NOT MET"


def cycle_target_lines(bare_us: float, workaround_us: float, cycles: dict[str, float]) -> list[str]:
    """The two absolute control-cycle targets, for each nav2_pyif row (label -> median µs):
    within 50 µs of the bare Zenoh round trip, and at least 2x below the rclpy workaround."""
    lines = []
    for label, median in cycles.items():
        overhead = median - bare_us
        lines.append(
            f"  nav2_pyif ({label}) over bare Zenoh: {overhead:+.1f} µs median "
            f"(target <= 50 µs): {verdict(overhead, '<=', 50, 1)}"
        )
    for label, median in cycles.items():
        ratio = workaround_us / median
        lines.append(
            f"  rclpy node / nav2_pyif ({label}): {ratio:.2f}x median (target >= 2x): "
            f"{verdict(ratio, '>=', 2, 2)}"
        )
    return lines


def _version(package: str) -> str:
    try:
        return metadata.version(package)
    except metadata.PackageNotFoundError:
        return "?"


def machine_description() -> str:
    cpu = platform.processor() or "?"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return (
        f"{cpu}, {os.cpu_count()} cores, Linux {platform.release()}, "
        f"Python {platform.python_version()}, eclipse-zenoh {_version('eclipse-zenoh')}, "
        f"msgpack {_version('msgpack')}, numpy {_version('numpy')}, "
        f"rclpy {_version('ros-jazzy-rclpy')} (Jazzy wheels, rmw_fastrtps_cpp)"
    )
