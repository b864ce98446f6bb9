"""The control cycle with the C++ plugin's client code on the client side (in production the
client is the plugin, not the Python reference client): bridge_plugin/bench's
nav2_pyif_cycle_bench against the very peers of `protocol` (planner hosts, bare queryable,
rclpy node), all rows in one run with interleaved rounds.

    scripts/build_cpp_bench.sh          # once; NAV2_PYIF_NAV2_SETUP: ROS 2, Nav2, zenoh-cpp
    nav2-pyif-bench cpp-cycle           # well under a minute
    nav2-pyif-bench cpp-cycle --quick   # a smoke run

The binary runs in the ROS environment of --setup (default $NAV2_PYIF_NAV2_SETUP); the peers
run in this Python's. Each nav2_pyif cycle is split into the C++ client's own work (the call
minus its Zenoh get: costmap check, encode, decode, command check), the get, and within that
the host's compute_ns (decoded request to reply body: session look-up, rclpy messages, the
planner, the checks; decode, encode and the Zenoh side are outside it). A 1000-pose set_plan,
protocol's plan row, is timed the same way: the plan path as the plugin sends it.
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

from nav2_pyif.common.option_types import positive_float

from nav2_pyif_bench.cycle_targets import cycle_target_lines
from nav2_pyif_bench.processes import free_port, peer_processes, ros_localhost_env
from nav2_pyif_bench.protocol_bench import (
    BARE_KEY,
    INPROC_KEY,
    KEY,
    add_rounds_and_rate,
    peer_commands,
    progress,
)
from nav2_pyif_bench.stats import Summary, header_row, verdict

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


def binary_path(
    given: str | None, default: Path = DEFAULT_BINARY, what: str = "bench binary"
) -> Path:
    """``given``, else ``default``: an executable scripts/build_cpp_bench.sh built, or a
    BenchSetupError saying how to build it."""
    binary = Path(given) if given else default
    if not (binary.is_file() and os.access(binary, os.X_OK)):
        raise BenchSetupError(f"no C++ {what} at {binary}: {BUILD_HINT}")
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
        *("--rounds", str(args.rounds), "--calls", str(args.calls)),
        *("--paced-calls", str(args.paced_calls), "--rate", str(args.rate)),
    ]
    script = f"source {shlex.quote(setup)} >/dev/null && exec {shlex.join(command)}"
    with peer_processes(peer_commands(host_port, inproc_port, bare_port), env):
        progress(f"running {binary.name} in the environment of {setup}")
        # stderr passes through: the binary's progress and its reason when it fails.
        result = subprocess.run(
            ["bash", "-c", script],
            env=ros_environment(env),
            stdout=subprocess.PIPE,
            text=True,
            timeout=args.timeout,
        )
    if result.returncode != 0:
        raise RuntimeError(f"{binary.name} failed (exit {result.returncode}); see above")
    output = json.loads(result.stdout)
    rows: dict[str, list[int]] = output["rows"]
    for name in ("pyif", "pyif_plan", "pyif_inproc"):  # the client's own work: call minus get
        pairs = zip(rows[name], rows[f"{name}.query"], strict=True)
        rows[f"{name}.client"] = [total - query for total, query in pairs]
    return {
        "backend": output["backend"],
        "rate": args.rate,
        "cycle": {k: asdict(Summary.of_ns(v)) for k, v in rows.items()},
    }


def report(results: dict[str, Any]) -> str:
    c = {k: Summary(**v) for k, v in results["cycle"].items()}
    lines = [
        "control cycle, C++ client (the plugin's ControllerSession + ZenohTransport, "
        f"{results['backend']}): PoseStamped + Twist in, TwistStamped out (trivial planner)",
        header_row(),
        c["bare"].row("bare Zenoh get -> empty reply"),
        c["host_floor"].row("host's cheapest reply (SessionUnknown)"),
    ]

    def split(name: str, label: str, handler: str) -> list[str]:
        """A call's row, then its C++ client work, its get, and the host's part of that."""
        return [
            c[name].row(label),
            c[f"{name}.client"].row("  of which C++ client (encode..decode)"),
            c[f"{name}.query"].row("  of which Zenoh get -> host -> reply"),
            c[f"{name}.handler"].row(f"    of which {handler}"),
        ]

    for name, label in (
        ("pyif", "nav2_pyif cycle, worker process (default)"),
        ("pyif_inproc", "nav2_pyif cycle, --isolation none"),
    ):
        lines += split(name, label, "planner call (compute_ns)")
    lines.append(c["rclcpp"].row("rclpy node via rclcpp client (workaround)"))
    plan = c["pyif_plan"]
    lines.append("1000-pose plan, C++ client (ControllerSession::set_plan, worker process)")
    lines += split("pyif_plan", "nav2_pyif set_plan", "host handler (compute_ns)")
    lines += [
        f"  over the cycle: {plan.median_us - c['pyif'].median_us:+.1f} µs median; "
        f"target <= 1 ms: {verdict(plan.median_us, '<=', 1000, 1)}",
    ]
    paced = [
        ("bare", "bare Zenoh get"),
        ("pyif", "nav2_pyif cycle, worker process"),
        ("pyif_plan", "nav2_pyif set_plan, 1000 poses, worker"),
        ("pyif_inproc", "nav2_pyif cycle, --isolation none"),
        ("rclcpp", "rclpy node via rclcpp client"),
    ]
    if "pyif.paced" in c:
        lines.append(
            f"  at a real control rate ({results.get('rate', 20):g} Hz, rows spread over "
            "the period):"
        )
        lines += [c[f"{n}.paced"].row(f"  {label}") for n, label in paced if f"{n}.paced" in c]
    lines += cycle_target_lines(c)
    return "\n".join(lines)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--binary", help=f"nav2_pyif_cycle_bench (default: {DEFAULT_BINARY.relative_to(ROOT)})"
    )
    parser.add_argument(
        "--setup", help="ROS 2 setup script the binary runs in (default: $NAV2_PYIF_NAV2_SETUP)"
    )
    add_rounds_and_rate(parser, paced_calls=300, none_paced=True)
    parser.add_argument(
        "--timeout",
        type=positive_float,
        default=900.0,
        metavar="SECONDS",
        help="seconds for the binary, > 0 (default 900)",
    )


def apply_quick(args: argparse.Namespace) -> argparse.Namespace:
    if args.quick:
        args.rounds, args.calls, args.paced_calls = 2, 50, 20
    return args
