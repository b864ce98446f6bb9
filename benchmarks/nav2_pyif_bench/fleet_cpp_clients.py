"""The robots of ``nav2-pyif-bench fleet --cpp-clients``: bridge_plugin/bench's
nav2_pyif_fleet_client, the plugin's own client code (ControllerSession over ZenohTransport),
a few processes of many robots each. On the 2-core benchmark machine the Python clients cost
more CPU per call than the host; these cost what the plugin costs a robot, so the host's
limit shows. Built by scripts/build_cpp_bench.sh; runs in the ROS environment of --setup.
"""

from __future__ import annotations

import json
import math
import shlex
import subprocess
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from nav2_pyif_bench.cpp_cycle_bench import ROOT, binary_path, ros_environment, setup_script
from nav2_pyif_bench.fleet_planners import FleetPlanner, scan

DEFAULT_CLIENT = ROOT / "build" / "cpp_bench" / "nav2_pyif_fleet_client"
PROCESSES = 2  # one per core: each a thread per robot, as a controller_server's plugins


def client_binary(given: str | None) -> Path:
    return binary_path(given, DEFAULT_CLIENT, "fleet client")


def _scan_file(directory: Path) -> Path:
    """The benchmark's scan (fleet_planners.scan) as ROS serializes it: what the plugin sends."""
    from nav2_pyif._ros_types import serialize

    path = directory / "scan.cdr"
    path.write_bytes(serialize(scan()))
    return path


def run_cpp_clients(
    endpoint: str,
    robots: int,
    planner: FleetPlanner,
    seconds: float,
    period: float,
    binary: Path,
    setup: str | None,
    on_go: Callable[[float], None],
) -> tuple[list[tuple[float, bool]], list[str]]:
    """Every robot's (latency [s], ok) per cycle and the distinct errors. ``on_go`` is called
    once every robot is set up, with the time.monotonic() their cycles start at."""
    setup = setup_script(setup)
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_fleet_cpp_") as tmp:
        common = ["--endpoint", endpoint, "--seconds", f"{seconds:g}", "--rate", f"{1 / period:g}"]
        for name, value in planner.params.items():
            common += ["--param", f"{name}={value}"]
        if planner.scan:
            common += ["--scan", str(_scan_file(Path(tmp)))]
        chunk = -(-robots // PROCESSES)  # consecutive indices per process
        processes: list[tuple[subprocess.Popen[str], list[int]]] = []
        try:
            for first in range(0, robots, chunk):
                count = min(chunk, robots - first)
                command = [str(binary), *common, "--first", str(first), "--count", str(count)]
                indices = list(range(first, first + count))
                script = f"source {shlex.quote(setup)} >/dev/null && exec {shlex.join(command)}"
                proc = subprocess.Popen(
                    ["bash", "-c", script],
                    env=ros_environment({}),
                    stdin=subprocess.PIPE,
                    stdout=subprocess.PIPE,
                    text=True,
                )
                processes.append((proc, indices))
            failed: list[str] = []
            for proc, indices in processes:  # every robot configured, compiled and warm
                assert proc.stdout is not None
                for _ in indices:
                    line = proc.stdout.readline()
                    if not line:
                        raise RuntimeError(f"{binary.name} ended while its robots set up")
                    if line.startswith("failed"):
                        failed.append(line.strip())
            start_ns = time.time_ns() + 1_000_000_000
            started = time.monotonic() + 1.0
            for proc, _ in processes:
                assert proc.stdin is not None
                proc.stdin.write(f"go {start_ns}\n")
                proc.stdin.flush()
            on_go(started)
            samples: list[tuple[float, bool]] = []
            errors: list[str] = list(failed)
            for proc, indices in processes:
                try:
                    out, _ = proc.communicate(timeout=seconds + 120)
                except subprocess.TimeoutExpired:
                    # A robot's call that never ended (no reply and no end of replies from
                    # Zenoh): its process's robots count as missing every period, and the
                    # other sizes of the run go on.
                    proc.kill()
                    proc.communicate()
                    samples += [(math.nan, False)] * (len(indices) * round(seconds / period))
                    errors.append(
                        f"{binary.name} robots {indices[0]}..{indices[-1]}: the process did "
                        f"not end {seconds + 120:g} s after its start; its samples are lost"
                    )
                    continue
                result: dict[str, Any] = json.loads(out.strip().splitlines()[-1])
                samples += [(ns / 1e9, bool(ok)) for ns, ok in result["samples"]]
                errors += result["errors"]
                if proc.returncode != 0:
                    raise RuntimeError(f"{binary.name} failed (exit {proc.returncode})")
            return samples, errors
        finally:  # also on a signal or an error: no client process is left behind
            for proc, _ in processes:
                if proc.poll() is None:
                    proc.terminate()
                    proc.wait(10)
