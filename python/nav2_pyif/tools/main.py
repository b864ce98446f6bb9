"""``nav2-pyif``: the project's command-line tools."""

from __future__ import annotations

import argparse
import logging
import sys

from nav2_pyif.common.option_types import positive_float
from nav2_pyif.common.signals import Interrupted, raise_on_signals
from nav2_pyif.common.zenoh_config import add_zenoh_arguments
from nav2_pyif.replay.cli import add_replay_parser
from nav2_pyif.runner.cli import add_sim_parser
from nav2_pyif.tools.hosts import add_hosts_parser
from nav2_pyif.tools.record import add_record_parser
from nav2_pyif.tools.router import add_router_parser


def add_reload_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "reload",
        help="hot-swap the planner served on a key (no Nav2 restart)",
        description="Ask the planner host serving KEY to load a new planner, or re-import "
        "the current one, while Nav2 keeps calling: sessions carry over.",
    )
    p.add_argument(
        "--key", required=True, metavar="PREFIX", help="the key prefix the planner is served on"
    )
    p.add_argument(
        "--planner",
        metavar="MODULE:CLASS",
        help="the planner to load (default: re-import the current one)",
    )
    p.add_argument(
        "--module", metavar="MODULE", help="a module of plain functions (function-delegate style)"
    )
    p.add_argument(
        "--delegate",
        action="append",
        default=[],
        metavar="ROLE=FUNCTION",
        help="role -> function of --module, repeatable or comma-separated",
    )
    p.add_argument(
        "--allow-type-change",
        action="store_true",
        help="let the new planner be of another plugin type than the key serves (e.g. a "
        "global planner on a controller's key); refused otherwise, and always while a "
        "session is live",
    )
    p.add_argument(
        "--timeout",
        type=positive_float,
        default=60.0,
        metavar="SECONDS",
        help="how long to wait for a router and a host on KEY (a host just started is "
        "waited for), then how long the host may take to load the new version, > 0 "
        "(default 60)",
    )
    add_zenoh_arguments(p, default_mode="client")
    p.set_defaults(func=run_reload)


def run_reload(args: argparse.Namespace) -> int:
    from nav2_pyif.client.hosts import reached
    from nav2_pyif.common.reach import open_tool_session, unreachable
    from nav2_pyif.common.zenoh_config import options_from_args
    from nav2_pyif.exceptions import PlannerLoadError
    from nav2_pyif.roles import parse_delegates
    from nav2_pyif.tools.admin import NoPlannerHost, request_reload

    def say(message: str) -> None:
        print(f"nav2-pyif reload: {message}", file=sys.stderr, flush=True)

    options = options_from_args(args)
    try:
        session = open_tool_session(options, "nav2-pyif reload", args.timeout)
    except (ConnectionError, FileNotFoundError) as exc:
        say(str(exc))
        return 1
    try:
        delegates = parse_delegates(args.delegate) if args.delegate else None
        print(
            request_reload(
                session,
                args.key,
                planner=args.planner,
                module=args.module,
                delegates=delegates,
                allow_type_change=args.allow_type_change,
                timeout=args.timeout,
                wait=args.timeout,
                on_waiting=say,
            )
        )
        return 0
    except NoPlannerHost as exc:
        # a peer opens without reaching anything: say where it tried instead
        say(str(exc) if reached(session) else f"no host on {args.key}: {unreachable(options)}")
        return 1
    except (PlannerLoadError, TimeoutError) as exc:
        say(str(exc))
        return 1
    finally:
        session.close()


#: Commands that live with the reference planners, named by import path (nav2_pyif never
#: imports nav2_pyif_planners): name -> (module whose main(argv, prog) runs it, help).
PLANNERS_COMMANDS = {
    "learn": (
        "nav2_pyif_planners.learned.cli",
        "train a learned controller on MPPI demonstrations offline, and drive it",
    ),
}


def add_planners_commands(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    for name, (module, what) in PLANNERS_COMMANDS.items():
        p = subparsers.add_parser(name, help=what, add_help=False)  # its own parser helps
        p.set_defaults(func=run_by_path, command=(name, module))


def run_by_path(args: argparse.Namespace) -> int:
    """Run the command's module's ``main`` with the command's own arguments."""
    import importlib

    name, module = args.command
    try:
        command = importlib.import_module(module)
    except ImportError as exc:
        print(
            f"nav2-pyif {name}: needs the reference planners ({module}: pip install ./planners "
            f"in a clone, the distribution nav2-pyif-planners): {exc}",
            file=sys.stderr,
        )
        return 2
    code: int = command.main(args.rest, prog=f"nav2-pyif {name}")
    return code


def build_parser() -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    """The top-level parser, and each command's own parser by name."""
    parser = argparse.ArgumentParser(prog="nav2-pyif", description="nav2_pyif tools")
    subparsers = parser.add_subparsers(required=True, metavar="COMMAND", dest="command_name")
    add_sim_parser(subparsers)
    add_planners_commands(subparsers)
    add_reload_parser(subparsers)
    add_router_parser(subparsers)
    add_hosts_parser(subparsers)
    add_record_parser(subparsers)
    add_replay_parser(subparsers)
    return parser, dict(subparsers.choices)


def main(argv: list[str] | None = None) -> int:
    parser, commands = build_parser()
    args, rest = parser.parse_known_args(argv)
    if args.func is run_by_path:  # a planners' command parses its own arguments
        args.rest = rest
    elif rest:  # the command's own usage: the options it does take
        commands[args.command_name].error(f"unrecognized arguments: {' '.join(rest)}")
    logging.basicConfig(level=logging.WARNING, format="[%(levelname)s] [%(name)s] %(message)s")
    try:
        raise_on_signals()  # every command cleans up and exits 128 + signum on a signal
        code: int = args.func(args)
    except Interrupted as exc:
        print(f"nav2-pyif: stopped by {exc.name}", file=sys.stderr)
        return exc.exit_code
    return code


if __name__ == "__main__":
    sys.exit(main())
