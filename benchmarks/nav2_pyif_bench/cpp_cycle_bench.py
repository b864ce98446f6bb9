"""The control cycle with the C++ plugin's client code on the client side (in production the
client is the plugin, not the Python reference client): bridge_plugin/bench's
nav2_pyif_cycle_bench against the very peers of `protocol` (planner hosts, bare queryable,
rclpy node), all rows in one run with interleaved rounds.

    scripts/build_cpp_bench.sh          # once; NAV2_PYIF_NAV2_SETUP: ROS 2, Nav2, zenoh-cpp
    nav2-pyif-bench cpp-cycle           # about three minutes: back to back, then at 20 Hz
    nav2-pyif-bench cpp-cycle --quick   # a smoke run

The binary runs in the ROS environment of --setup (default $NAV2_PYIF_NAV2_SETUP); the peers
run in this Python's. Each nav2_pyif cycle is split into the C++ client's own work (the call
minus its Zenoh get: costmap check, encode, decode, command check), the get, and within that
the host's compute_ns (decoded request to reply body: session look-up, rclpy messages, the
planner, the checks; decode, encode and the Zenoh side are outside it).

Then the same rows at a real control rate (--rate, default 20 Hz): each call starts on a fixed
schedule, so every process sleeps between calls as under Nav2, and p99 is compared with the
median.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import subprocess
import sys
from dataclasses import asdict
from pathlib import Path
from typing import Any

from nav2_pyif_bench.processes import free_port, peer_processes, ros_localhost_env
from nav2_pyif_bench.protocol_bench import BARE_KEY, INPROC_KEY, KEY, peer_commands, progress
from nav2_pyif_bench.stats import Summary, header_row

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_BINARY = ROOT / "build" / "cpp_bench" / "nav2_pyif_cycle_bench"
BUILD_HINT = "build it with scripts/build_cpp_bench.sh (NAV2_PYIF_NAV2_SETUP names a ROS 2 setup)"
# What the project's venv puts in the environment, kept out of the ROS one the binary needs.
VENV_VARIABLES = (
    "PYTHONPATH",
    "LD_LIBRARY_PATH",
    "VIRTUAL_ENV",
    "AMENT_PREFIX_PATH",
    "_ROS_WHEELS_BOOTSTRAP_COMPLETE",
)


class BenchSetupError(Exception):
    """The C++ bench cannot run here: the message says what to do."""


def setup_script(given: str | None) -> str:
    setup = given or os.environ.get("NAV2_PYIF_NAV2_SETUP")
    if not setup:
        setup = next(
            (
                f"/opt/ros/{d}/setup.bash"
                for d in ("jazzy", "kilted", "humble")
                if Path(f"/opt/ros/{d}/setup.bash").is_file()
            ),
            None,
        )
    if not setup or not Path(setup).is_file():
        raise BenchSetupError(
            f"no ROS 2 setup script ({setup or 'none given'}): pass --setup or set "
            "NAV2_PYIF_NAV2_SETUP to the setup script of the ROS 2 the binary was built against"
        )
    return setup


def binary_path(given: str | None) -> Path:
    binary = Path(given) if given else DEFAULT_BINARY
    if not (binary.is_file() and os.access(binary, os.X_OK)):
        raise BenchSetupError(f"no C++ bench binary at {binary}: {BUILD_HINT}")
    return binary


def ros_environment(extra: dict[str, str]) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in VENV_VARIABLES}
    venv_bin = str(Path(sys.prefix) / "bin")  # ROS setup scripts run python3 from PATH
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep) if p != venv_bin)
    return {**env, **extra}


def run(args: argparse.Namespace) -> dict[str, Any]:
    binary, setup = binary_path(args.binary), setup_script(args.setup)
    host_port, inproc_port, bare_port = free_port(), free_port(), free_port()
    env = ros_localhost_env()
    command = [
        str(binary),
        *("--bare", f"tcp/127.0.0.1:{bare_port}", "--bare-key", BARE_KEY),
        *("--host", f"tcp/127.0.0.1:{host_port}", "--key", KEY),
        *("--inproc", f"tcp/127.0.0.1:{inproc_port}", "--inproc-key", INPROC_KEY),
        "--rclcpp",
    ]
    results: dict[str, Any] = {"rate_hz": args.rate, "load": [os.getloadavg()[0]]}
    with peer_processes(peer_commands(host_port, inproc_port, bare_port), env):
        progress(f"running {binary.name} in the environment of {setup}")
        tight = ["--rounds", str(args.rounds), "--calls", str(args.calls)]
        results["backend"], results["cycle"] = _run_binary(command + tight, setup, env, args)
        if args.rate > 0:
            progress(f"the same rows at {args.rate:g} Hz")
            paced = ["--rounds", str(args.paced_rounds), "--calls", str(args.paced_calls)]
            paced += ["--period-ms", f"{1000.0 / args.rate:g}"]
            _, results["paced"] = _run_binary(command + paced, setup, env, args)
    results["load"].append(os.getloadavg()[0])
    return results


def _run_binary(
    command: list[str], setup: str, env: dict[str, str], args: argparse.Namespace
) -> tuple[str, dict[str, Any]]:
    """The binary's backend and each row's summary."""
    backend, rows = run_binary(command, setup, env, args.timeout)
    for name in ("pyif", "pyif_inproc"):  # the client's own work: the call minus its get
        pairs = zip(rows[name], rows[f"{name}.query"], strict=True)
        rows[f"{name}.client"] = [total - query for total, query in pairs]
    return backend, {k: asdict(Summary.of_ns(v)) for k, v in rows.items()}


def run_binary(
    command: list[str], setup: str, env: dict[str, str], timeout: float
) -> tuple[str, dict[str, list[int]]]:
    """Run the C++ bench in the ROS environment of ``setup``: its backend and samples [ns]."""
    script = f"source {shlex.quote(setup)} >/dev/null && exec {shlex.join(command)}"
    # stderr passes through: the binary's progress and its reason when it fails.
    result = subprocess.run(
        ["bash", "-c", script],
        env=ros_environment(env),
        stdout=subprocess.PIPE,
        text=True,
        timeout=timeout,
    )
    if result.returncode != 0:
        raise RuntimeError(f"{Path(command[0]).name} failed (exit {result.returncode}); see above")
    output = json.loads(result.stdout)
    return str(output["backend"]), output["rows"]


def report(results: dict[str, Any]) -> str:
    c = {k: Summary(**v) for k, v in results["cycle"].items()}
    lines = [
        "control cycle, C++ client (the plugin's ControllerSession + ZenohTransport, "
        f"{results['backend']}): PoseStamped + Twist in, TwistStamped out (trivial planner)",
        f"load average {results['load'][0]:.2f} at the start, {results['load'][1]:.2f} at the end",
        *_table(c),
    ]
    paced = {k: Summary(**v) for k, v in results.get("paced", {}).items()}
    if paced:
        lines += [f"the same rows at {results['rate_hz']:g} Hz (one call every period)"]
        lines += _table(paced)
    lines += cycle_targets(c, paced)
    return "\n".join(lines)


def _table(c: dict[str, Summary]) -> list[str]:
    lines = [
        header_row(),
        c["bare"].row("bare Zenoh get -> empty reply"),
        c["host_floor"].row("host's cheapest reply (SessionUnknown)"),
    ]
    for name, label in (
        ("pyif", "nav2_pyif cycle, worker process (default)"),
        ("pyif_inproc", "nav2_pyif cycle, --isolation none"),
    ):
        lines += [
            c[name].row(label),
            c[f"{name}.client"].row("  of which C++ client (encode..decode)"),
            c[f"{name}.query"].row("  of which Zenoh get -> host -> reply"),
            c[f"{name}.handler"].row("    of which planner call (compute_ns)"),
        ]
    lines.append(c["rclcpp"].row("rclpy node via rclcpp client (workaround)"))
    return lines


def cycle_targets(c: dict[str, Summary], paced: dict[str, Summary]) -> list[str]:
    """Issue 15's targets for the default (worker process) cycle, as ratios within one run."""
    worker, inproc, bare, ros = c["pyif"], c["pyif_inproc"], c["bare"], c["rclcpp"]
    checks = [
        ("median over bare Zenoh's", worker.median_us / bare.median_us, "<= 1.5", 1.5, False),
        (
            "median over --isolation none's",
            worker.median_us / inproc.median_us,
            "<= 1.1",
            1.1,
            False,
        ),
        ("rclpy node's median over it", ros.median_us / worker.median_us, ">= 1.2", 1.2, True),
        ("rclpy node's p99 over it", ros.p99_us / worker.p99_us, ">= 2 (loaded)", 2.0, True),
    ]
    if paced:
        w = paced["pyif"]
        checks.append(
            ("p99 over median at the paced rate", w.p99_us / w.median_us, "<= 2", 2.0, False)
        )
    # What a target compares against, measured the same way: the floor no host can go below.
    context = [
        "  for comparison: host's cheapest reply over bare Zenoh's median "
        f"{c['host_floor'].median_us / bare.median_us:.2f}x, --isolation none's "
        f"{inproc.median_us / bare.median_us:.2f}x"
    ]
    if paced:
        context.append(
            "  for comparison, p99 over median at the paced rate: bare Zenoh get "
            f"{paced['bare'].p99_us / paced['bare'].median_us:.2f}x, --isolation none "
            f"{paced['pyif_inproc'].p99_us / paced['pyif_inproc'].median_us:.2f}x, rclpy node "
            f"{paced['rclcpp'].p99_us / paced['rclcpp'].median_us:.2f}x"
        )
    lines = []
    for label, ratio, wanted, bound, at_least in checks:
        met = ratio >= bound if at_least else ratio <= bound
        lines.append(
            f"  worker cycle {label}: {ratio:.2f}x (target {wanted}): {'MET' if met else 'NOT MET'}"
        )
    return lines + context


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--binary", help=f"nav2_pyif_cycle_bench (default: {DEFAULT_BINARY.relative_to(ROOT)})"
    )
    parser.add_argument(
        "--setup", help="ROS 2 setup script the binary runs in (default: $NAV2_PYIF_NAV2_SETUP)"
    )
    parser.add_argument("--rounds", type=int, default=10, help="interleaved rounds")
    parser.add_argument("--calls", type=int, default=300, help="calls per row and round")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds for the binary")
    parser.add_argument(
        "--rate", type=float, default=20.0, help="then the same rows at this rate [Hz]; 0: skip"
    )
    parser.add_argument("--paced-rounds", type=int, default=4, help="rounds at --rate")
    parser.add_argument("--paced-calls", type=int, default=100, help="calls per row and round")
    parser.add_argument("--quick", action="store_true", help="a short smoke run")


def apply_quick(args: argparse.Namespace) -> argparse.Namespace:
    if getattr(args, "quick", False):
        args.rounds, args.calls = 2, 50
        args.paced_rounds, args.paced_calls = 1, 10
    return args
