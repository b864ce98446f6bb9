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
