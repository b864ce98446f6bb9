"""Issue 15's question, measured with the C++ plugin's client: what does a query cost when a
second process answers it, through its own Zenoh session (routed by the host's session) or
through a pipe from the host's queryable (the supervisor's way)? Empty replies, no protocol:
only the hop. Each variant is the C++ bench's ``bare`` row against its own peer, the variants
alternating round by round.

    nav2-pyif-bench isolation-hop           # about a minute
"""

from __future__ import annotations

import argparse
from dataclasses import asdict
from typing import Any

from nav2_pyif_bench.cpp_cycle_bench import binary_path, run_binary, setup_script
from nav2_pyif_bench.processes import free_port, peer_processes
from nav2_pyif_bench.protocol_bench import progress
from nav2_pyif_bench.stats import Summary, header_row

KEY = "nav2_pyif/bench/hop"
VARIANTS = {
    "here": "answered in the listening process (the floor)",
    "pipe": "handed to a worker over a pipe (the supervisor)",
    "session": "answered by a worker's own Zenoh session",
}


def _peer(variant: str, port: int) -> list[str]:
    where = ["--listen", f"tcp/127.0.0.1:{port}", "--key", KEY]
    if variant == "here":
        return ["-m", "nav2_pyif_bench.bare_zenoh", *where]
    return ["-m", "nav2_pyif_bench.hop_peer", *where, "--via", variant]


def run(args: argparse.Namespace) -> dict[str, Any]:
    binary, setup = binary_path(args.binary), setup_script(args.setup)
    ports = {variant: free_port() for variant in VARIANTS}
    samples: dict[str, list[int]] = {variant: [] for variant in VARIANTS}
    with peer_processes({v: _peer(v, port) for v, port in ports.items()}, {}):
        for r in range(args.rounds):
            progress(f"isolation hop: round {r + 1}/{args.rounds}")
            for variant, port in ports.items():
                command = [str(binary), "--bare", f"tcp/127.0.0.1:{port}", "--bare-key", KEY]
                command += ["--rounds", "1", "--calls", str(args.calls)]
                _, rows = run_binary(command, setup, {}, args.timeout)
                samples[variant] += rows["bare"]
    return {"hop": {v: asdict(Summary.of_ns(s)) for v, s in samples.items()}}


def report(results: dict[str, Any]) -> str:
    hop = {v: Summary(**s) for v, s in results["hop"].items()}
    floor = hop["here"].median_us
    lines = ["an empty query from the C++ client, by who answers it", header_row(50)]
    for variant, label in VARIANTS.items():
        extra = hop[variant].median_us - floor
        lines.append(hop[variant].row(label, 50) + (f"  {extra:+.1f} µs" if extra else ""))
    return "\n".join(lines)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--binary", help="nav2_pyif_cycle_bench (default: build/cpp_bench/...)")
    parser.add_argument("--setup", help="ROS 2 setup script (default: $NAV2_PYIF_NAV2_SETUP)")
    parser.add_argument("--rounds", type=int, default=6, help="alternating rounds")
    parser.add_argument("--calls", type=int, default=500, help="calls per variant and round")
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per binary run")
