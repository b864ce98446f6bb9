"""``nav2-pyif router``: a Zenoh router in Python, for machines without ``zenohd``.

On a robot the router is usually rmw_zenoh's ``zenohd``; this one is for a GPU box or a
container compose file that should route between planner hosts and robots with nothing else
installed. It is an ordinary Zenoh session in router mode (eclipse-zenoh, the same version as
the host), running until SIGINT, SIGTERM or SIGHUP (then it exits with 128 + the signal's
number, as every nav2-pyif command: ``nav2_pyif.tools.main`` turns signals into Interrupted).

Zenoh's own warnings are logged (to stdout, after the "listening on" line): with TLS, every
refused link (no client certificate, one from another CA, plain TCP on a TLS port) says so.
``RUST_LOG`` chooses more, e.g. access control's decisions:
``RUST_LOG=zenoh=warn,zenoh::net::routing::interceptor::access_control=trace``.
"""

from __future__ import annotations

import argparse
import sys
import threading

import zenoh

from nav2_pyif.common.zenoh_config import ZenohOptions, add_endpoint_arguments, open_session

DEFAULT_LISTEN = "tcp/0.0.0.0:7447"


def add_router_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "router",
        help="run a Zenoh router (when no zenohd is at hand)",
        description="Run a Zenoh router: planner hosts and plugins connect to it and it "
        f"routes between them. Listens on {DEFAULT_LISTEN} unless --listen or a "
        "--zenoh-config file says otherwise; --connect joins other routers.",
    )
    add_endpoint_arguments(
        p,
        config_help="Zenoh JSON5 config file instead (its mode is set to router)",
        connect_help="another router to join, repeatable",
        listen_help=f"endpoint to listen on, repeatable (default: the config file's, else "
        f"{DEFAULT_LISTEN})",
    )
    p.set_defaults(func=run_router)


def run_router(args: argparse.Namespace) -> int:
    # The default endpoint only without a file: it would replace the file's listen endpoints.
    listen = list(args.listen) or ([] if args.zenoh_config else [DEFAULT_LISTEN])
    options = ZenohOptions(
        args.zenoh_config, list(args.connect), listen, mode="router", use_environment=False
    )
    try:
        session = open_session(options)
    except (ConnectionError, FileNotFoundError) as exc:
        print(f"nav2-pyif router: error: {exc}", file=sys.stderr)
        return 3
    where = ", ".join(options.listen) or f"the endpoints of {options.config_file}"
    print(f"zenoh router {session.info.zid()} listening on {where}", flush=True)
    zenoh.init_log_from_env_or("warn")  # $RUST_LOG, else Zenoh's warnings
    try:
        threading.Event().wait()  # until a signal raises Interrupted
    finally:
        session.close()
    return 0
