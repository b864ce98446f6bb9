"""nav2-pyif-bench: the project's benchmarks; each prints its figures (see BENCHMARKS.md).

nav2-pyif-bench protocol [--quick]             control cycle, plans, costmaps, throughput
nav2-pyif-bench cpp-cycle [--quick]            the control cycle with the C++ plugin's client
nav2-pyif-bench mppi [--batch-sizes 1000 2000]  the MPPI controllers through a host, both maps
nav2-pyif-bench mppi-profile [--cold]         where Nav2MPPI's cycle and compiled step spend time
nav2-pyif-bench mppi-fleet [--robots 1 5 10]   Nav2MPPI batched: CPU per robot-cycle at 20 Hz
nav2-pyif-bench mppi-traces DIR [--png P]      where the MPPI side-by-side's drives spend time
nav2-pyif-bench fleet [--robots 1 10 50]        N robots at 20 Hz on one host (--batch, --compare)
nav2-pyif-bench reliability [--calls 200000]    hot swap gaps, RSS over a long run
nav2-pyif-bench tls [--quick]                   the control cycle over TCP, mTLS, mTLS + ACL
nav2-pyif-bench host --connect E --key K        the control cycle against a running host
nav2-pyif-bench checkers [--quick]              the cycle with Python goal/progress checkers
nav2-pyif-bench path-handler [--quick]          Lyrical's cycle with a Python path handler
nav2-pyif-bench hops [--quick]                  one more hop: pipe, Zenoh thread, relay, router
nav2-pyif-bench layer [--quick]                 a Python costmap layer, 400 x 400 at 5 Hz
nav2-pyif-bench inputs [--quick]                a scan, a cloud, an image: protocol vs a topic
nav2-pyif-bench obstacles [--quick]             Costmap.obstacle_points() vs every lethal cell
nav2-pyif-bench record [--quick]                the control cycle with planner-host --record off/on
nav2-pyif-bench watch [--edits 20]              planner-host --watch: edit saved -> served
nav2-pyif-bench hostile [--seconds 300]         a fuzzing peer beside a 20 Hz client
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from nav2_pyif.common.option_types import non_negative_int, positive_float, positive_int
from nav2_pyif.common.signals import Interrupted, raise_on_signals

from nav2_pyif_bench import (
    checkers_bench,
    cpp_cycle_bench,
    fleet_bench,
    hop_bench,
    host_bench,
    hostile_bench,
    inputs_bench,
    layer_bench,
    mppi_bench,
    mppi_fleet,
    mppi_profile,
    mppi_traces,
    obstacles_bench,
    path_handler_bench,
    protocol_bench,
    record_bench,
    reliability_bench,
    tls_bench,
    watch_bench,
)
from nav2_pyif_bench.stats import machine_description


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="nav2-pyif-bench",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = parser.add_subparsers(dest="bench", required=True, metavar="BENCHMARK")
    protocol = sub.add_parser("protocol", help="the protocol beside bare Zenoh and rclpy")
    protocol_bench.add_arguments(protocol)
    cpp_cycle = sub.add_parser(
        "cpp-cycle", help="the control cycle with the C++ plugin's client code (built apart)"
    )
    cpp_cycle_bench.add_arguments(cpp_cycle)
    mppi = sub.add_parser("mppi", help="the MPPI controller's rate through a planner host")
    mppi.add_argument(
        "--batch-sizes",
        type=positive_int,
        nargs="+",
        default=[1000, 2000],
        help="rollouts per cycle to measure, each >= 1 (default 1000 2000)",
    )
    mppi.add_argument(
        "--map",
        nargs="+",
        default=["office", "cluttered"],
        help="bundled maps to drive (default office cluttered)",
    )
    mppi.add_argument(
        "--time-steps",
        type=positive_int,
        default=mppi_bench.TIME_STEPS,
        help=f"steps of 0.05 s per rollout, every controller (default {mppi_bench.TIME_STEPS})",
    )
    mppi.add_argument(
        "--controllers",
        nargs="+",
        default=mppi_bench.default_controllers(),
        help="default: mppi, and mppi_jax and mppi_nav2 (Nav2's MPPI in JAX) when JAX is installed",
    )
    profile = sub.add_parser("mppi-profile", help="the parts of Nav2MPPI's compiled step")
    profile.add_argument(
        "--rollouts",
        type=positive_int,
        nargs="+",
        default=[1000, 2000],
        help="batch sizes to profile (default 1000 2000)",
    )
    profile.add_argument(
        "--cycle-only",
        action="store_true",
        help="only the whole cycle as the host runs it, not the step's parts compiled apart",
    )
    profile.add_argument(
        "--repeat", type=positive_int, default=200, help="timed runs per part (default 200)"
    )
    profile.add_argument(
        "--cold",
        action="store_true",
        help="also the whole cycle after a read larger than the CPU's last cache, and one "
        "every 50 ms (20 Hz, as Nav2 calls it): what each call pays when it starts cold",
    )
    traces = sub.add_parser(
        "mppi-traces",
        help="the MPPI side-by-side's drives (NAV2_PYIF_MPPI_TRACES): per drive and drawn",
    )
    traces.add_argument("directory", help="the traces directory the side-by-side wrote")
    traces.add_argument("--png", metavar="PATH", help="draw one drive's commands over time")
    traces.add_argument(
        "--drive",
        type=non_negative_int,
        default=2,
        help="the drive drawn (default 2: the first goal again)",
    )
    mppi_fleet_parser = sub.add_parser(
        "mppi-fleet", help="Nav2MPPI batched: N robots in one call at 20 Hz, CPU per robot"
    )
    mppi_fleet_parser.add_argument(
        "--robots",
        type=positive_int,
        nargs="+",
        default=[1, 5, 10, 20, 30, 35, 40],
        help="fleet sizes (default 1 5 10 20 30 35 40)",
    )
    mppi_fleet_parser.add_argument(
        "--rollouts", type=positive_int, default=1000, help="batch_size per robot (default 1000)"
    )
    mppi_fleet_parser.add_argument(
        "--seconds", type=positive_float, default=5.0, help="seconds per fleet size (default 5)"
    )
    mppi_fleet_parser.add_argument(
        "--cpp-ms",
        type=positive_float,
        nargs="+",
        default=[2.1, 3.0],
        help="the C++ MPPI's compute per cycle to compare with [ms] (default 2.1 3.0: the "
        "low end of this machine type's C++ figures and the side-by-side harness's median)",
    )
    mppi_fleet_parser.add_argument(
        "--lanes",
        type=positive_int,
        nargs="+",
        help="JAX CPU devices the robots are spread over, side by side, a process each "
        "(e.g. 1 2; default: one process, one device per core as Nav2MPPI takes)",
    )
    mppi_fleet_parser.add_argument(
        "--rounds",
        type=positive_int,
        default=3,
        help="with --lanes: interleaved rounds of every lane count (default 3)",
    )
    fleet = sub.add_parser("fleet", help="N robots at 20 Hz on one planner host")
    fleet.add_argument(
        "--robots",
        type=positive_int,
        nargs="+",
        default=[1, 10, 50],
        help="fleet sizes to measure, each >= 1 (default 1 10 50)",
    )
    fleet.add_argument(
        "--seconds",
        type=positive_float,
        default=20.0,
        help="seconds per fleet size, > 0 (default 20)",
    )
    fleet.add_argument(
        "--isolation",
        choices=["process", "none"],
        default="process",
        help="the planner host's --isolation (default process)",
    )
    fleet.add_argument(
        "--planner",
        choices=["trivial", "learned", "mppi_jax", "mppi_nav2"],
        default="trivial",
        help="the controller every robot calls (default trivial: the path alone)",
    )
    fleet.add_argument(
        "--rollouts",
        type=positive_int,
        default=1000,
        help="mppi_jax's and mppi_nav2's batch_size (default 1000)",
    )
    fleet.add_argument(
        "--batch", action="store_true", help="one worker for all robots, cycles batched"
    )
    fleet.add_argument(
        "--batch-window",
        type=positive_float,
        default=5.0,
        metavar="MS",
        help="planner-host --batch-window with --batch or --compare (default 5)",
    )
    fleet.add_argument(
        "--compare",
        action="store_true",
        help="each fleet size with one worker per robot, then batched",
    )
    fleet.add_argument(
        "--xla-single-thread",
        action="store_true",
        help="the host's JAX runs each computation on one thread (XLA_FLAGS): on a small CPU "
        "shared with the clients, no core is lost to XLA's thread pool",
    )
    fleet.add_argument(
        "--batch-robots",
        type=positive_int,
        nargs="+",
        metavar="N",
        help="with --compare: the fleet sizes of the batched mode (default: --robots)",
    )
    fleet.add_argument(
        "--stop-at-miss",
        action="store_true",
        help="a mode stops at the first fleet size that missed a period",
    )
    fleet.add_argument(
        "--cpp-clients",
        action="store_true",
        help="the robots as the plugin's C++ client code (nav2_pyif_fleet_client, built by "
        "scripts/build_cpp_bench.sh), 2 processes, instead of Python clients in 4",
    )
    fleet.add_argument(
        "--fleet-client",
        metavar="BINARY",
        help="with --cpp-clients: the client (default build/cpp_bench/nav2_pyif_fleet_client)",
    )
    fleet.add_argument(
        "--setup",
        metavar="SCRIPT",
        help="with --cpp-clients: the ROS 2 setup script it was built against (default "
        "$NAV2_PYIF_NAV2_SETUP)",
    )
    fleet.add_argument("--plot", metavar="PNG", help="draw latency and misses against robots")
    reliability = sub.add_parser("reliability", help="hot swap gap, memory over a long run")
    reliability.add_argument(
        "--swaps", type=positive_int, default=6, help="hot swaps under load, >= 1 (default 6)"
    )
    reliability.add_argument(
        "--calls",
        type=positive_int,
        default=200_000,
        help="control cycles of the long run, >= 1 (default 200000)",
    )
    reliability.add_argument(
        "--cycles",
        type=positive_int,
        default=100,
        help="configure/activate/deactivate/cleanup cycles, >= 1 (default 100)",
    )
    hostile = sub.add_parser(
        "hostile", help="a fuzzing peer on every key of a live host, beside a 20 Hz client"
    )
    hostile.add_argument(
        "--seconds", type=positive_float, default=300.0, help="how long it fuzzes (default 300)"
    )
    hostile.add_argument(
        "--seed", type=positive_int, default=1, help="of the mutations, >= 1 (default 1)"
    )
    tls = sub.add_parser("tls", help="TLS's cost: the control cycle over TCP and mutual TLS")
    protocol_bench.add_round_arguments(tls)
    host = sub.add_parser(
        "host", help="the control cycle against a planner host already running (--connect)"
    )
    host_bench.add_arguments(host)
    record = sub.add_parser("record", help="the control cycle with planner-host --record off/on")
    record_bench.add_arguments(record)
    checkers = sub.add_parser(
        "checkers", help="the control cycle with Python goal and progress checkers"
    )
    checkers_bench.add_arguments(checkers)
    handler = sub.add_parser(
        "path-handler", help="Lyrical's control cycle with a Python path handler"
    )
    path_handler_bench.add_arguments(handler)
    hops = sub.add_parser(
        "hops", help="what one more hop costs: worker pipe, Zenoh thread, relay, router"
    )
    hop_bench.add_arguments(hops)
    layer = sub.add_parser("layer", help="a Python costmap layer on a 400 x 400 grid at 5 Hz")
    layer_bench.add_arguments(layer)
    obstacles = sub.add_parser(
        "obstacles", help="Costmap.obstacle_points() beside every lethal cell, per costmap"
    )
    obstacles_bench.add_arguments(obstacles)
    inputs = sub.add_parser(
        "inputs", help="a scan, a cloud, an image with each cycle, beside an rclpy topic"
    )
    inputs_bench.add_arguments(inputs)
    watch = sub.add_parser(
        "watch", help="planner-host --watch: from saving a planner's file to its first reply"
    )
    watch_bench.add_arguments(watch)
    for p in sub.choices.values():
        p.add_argument("--json", metavar="PATH", help="also write the figures as JSON")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args, rest = parser.parse_known_args(argv)
    if rest:  # the benchmark's own usage: the options it does take
        benchmarks = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        benchmarks.choices[args.bench].error(f"unrecognized arguments: {' '.join(rest)}")
    raise_on_signals()  # SIGINT/SIGTERM/SIGHUP: every peer process stopped, exit 128 + signum
    try:
        return run(args)
    except Interrupted as exc:
        print(f"nav2-pyif-bench {args.bench}: stopped by {exc.name}", file=sys.stderr)
        return exc.exit_code


def run(args: argparse.Namespace) -> int:
    print(f"machine: {machine_description()}\n", flush=True)
    if args.bench == "cpp-cycle":
        try:
            results = cpp_cycle_bench.run(cpp_cycle_bench.apply_quick(args))
        except cpp_cycle_bench.BenchSetupError as exc:
            print(f"nav2-pyif-bench cpp-cycle: {exc}", file=sys.stderr)
            return 2
        text = cpp_cycle_bench.report(results)
    elif args.bench == "protocol":
        results = protocol_bench.run(protocol_bench.apply_quick(args))
        text = protocol_bench.report(results)
    elif args.bench == "host":
        results = host_bench.run(args)
        text = host_bench.report(results)
    elif args.bench == "record":
        results = record_bench.run(args)
        text = record_bench.report(results)
    elif args.bench == "checkers":
        results = checkers_bench.run(args)
        text = checkers_bench.report(results)
    elif args.bench == "path-handler":
        results = path_handler_bench.run(args)
        text = path_handler_bench.report(results)
    elif args.bench == "inputs":
        results = inputs_bench.run(args)
        text = inputs_bench.report(results)
    elif args.bench == "layer":
        results = layer_bench.run(args)
        text = layer_bench.report(results)
    elif args.bench == "hostile":
        results = hostile_bench.run(args.seconds, args.seed)
        text = hostile_bench.report(results)
    elif args.bench == "obstacles":
        results = obstacles_bench.run(args)
        text = obstacles_bench.report(results)
    elif args.bench == "watch":
        results = watch_bench.run(args)
        text = watch_bench.report(results)
    elif args.bench == "tls":
        results = tls_bench.run(protocol_bench.apply_quick_rounds(args))
        text = tls_bench.report(results)
    elif args.bench == "mppi":
        results = mppi_bench.run(args)
        text = mppi_bench.report(results)
    elif args.bench == "mppi-profile":
        results = mppi_profile.run(args)
        text = mppi_profile.report(results)
    elif args.bench == "mppi-traces":
        try:
            results = mppi_traces.run(args)
        except (FileNotFoundError, ValueError) as exc:
            print(f"nav2-pyif-bench mppi-traces: {exc}", file=sys.stderr)
            return 2
        text = mppi_traces.report(results)
    elif args.bench == "mppi-fleet":
        results = mppi_fleet.run(args)
        text = mppi_fleet.report(results)
    elif args.bench == "hops":
        results = hop_bench.run(hop_bench.apply_quick(args))
        text = hop_bench.report(results)
    elif args.bench == "fleet":
        try:
            results = fleet_bench.run(args)
        except cpp_cycle_bench.BenchSetupError as exc:
            print(f"nav2-pyif-bench fleet: {exc}", file=sys.stderr)
            return 2
        text = fleet_bench.report(results)
        if args.plot:
            from nav2_pyif_bench.fleet_plot import plot_fleet

            plot_fleet(results, Path(args.plot), machine_description())
            text += f"\nwrote {args.plot}"
    else:
        results = reliability_bench.run(args)
        text = reliability_bench.report(results)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
