"""Zenoh session configuration from a JSON5 file or command-line flags (rmw_zenoh-style).

Precedence: ``--zenoh-config FILE`` > ``$NAV2_PYIF_ZENOH_CONFIG`` > the default file of the
session's mode; then ``--connect`` / ``--listen`` / ``--mode`` override. The defaults are files
(nav2_pyif_protocol/zenoh/<mode>.json5, nav2_pyif_protocol.zenoh_defaults), chosen as rmw_zenoh
chooses them: the planner host is a peer that connects to a Zenoh router on tcp/localhost:7447
and listens on a free local port; the tools (``nav2-pyif reload``, ...) are clients of that
router, as ros2cli's are, and as the C++ plugin is (its zenoh-c backend loads the same client
file). Multicast scouting is off. With ``--listen`` and no ``--connect``, the host connects
nowhere and waits for plugins to dial it.
"""

from __future__ import annotations

import argparse
import json
import os
from dataclasses import dataclass, field

import zenoh
from nav2_pyif_protocol import zenoh_defaults

from nav2_pyif.common.option_types import FromVariable, endpoint, zenoh_config_file

DEFAULT_ROUTER = "tcp/localhost:7447"  # the default files' connect endpoint, for messages
CONFIG_ENV = "NAV2_PYIF_ZENOH_CONFIG"


@dataclass
class ZenohOptions:
    config_file: str | None = None
    connect: list[str] = field(default_factory=list)
    listen: list[str] = field(default_factory=list)
    mode: str | None = None
    multicast_scouting: bool = False
    use_environment: bool = True  # read $NAV2_PYIF_ZENOH_CONFIG when no file is given
    default_mode: str = "peer"  # the mode when neither --mode nor a config file gives one


def add_endpoint_arguments(
    group: argparse._ArgumentGroup | argparse.ArgumentParser,
    *,
    config_help: str,
    connect_help: str,
    listen_help: str,
    default: str | None = None,
) -> None:
    """--zenoh-config, --connect and --listen (repeatable), shared by the host and router;
    each checked at parse time (a usage error, not Zenoh's error when the session opens)."""
    group.add_argument(
        "--zenoh-config", type=zenoh_config_file, default=default, metavar="FILE", help=config_help
    )
    for flag, text in (("--connect", connect_help), ("--listen", listen_help)):
        group.add_argument(
            flag, action="append", type=endpoint, default=[], metavar="ENDPOINT", help=text
        )


def add_zenoh_arguments(parser: argparse.ArgumentParser, default_mode: str = "peer") -> None:
    """The Zenoh options of a command; ``default_mode``: "peer" for a planner host (it also
    listens on a free local port), "client" for a tool that only asks."""
    parser.set_defaults(zenoh_default_mode=default_mode)
    group = parser.add_argument_group("zenoh")
    add_endpoint_arguments(
        group,
        # The variable as the option's default: argparse checks a string default with the
        # option's type, so a missing or unreadable file is a usage error here too.
        default=FromVariable(path, CONFIG_ENV) if (path := os.environ.get(CONFIG_ENV)) else None,
        config_help=f"Zenoh JSON5 config file (default: ${CONFIG_ENV}, else built-in)",
        connect_help=f"endpoint to connect to, repeatable (default: {DEFAULT_ROUTER})",
        listen_help="endpoint to listen on, repeatable, e.g. tcp/127.0.0.1:7447 "
        "(use when no Zenoh router runs)",
    )
    group.add_argument(
        "--mode",
        choices=["peer", "client", "router"],
        help=f"Zenoh session mode (default: {default_mode})",
    )
    group.add_argument(
        "--multicast-scouting",
        action="store_true",
        help="enable multicast scouting (off by default, as in rmw_zenoh)",
    )


def options_from_args(args: argparse.Namespace) -> ZenohOptions:
    return ZenohOptions(
        args.zenoh_config,
        list(args.connect),
        list(args.listen),
        args.mode,
        args.multicast_scouting,
        default_mode=getattr(args, "zenoh_default_mode", "peer"),
    )


def build_config(options: ZenohOptions) -> zenoh.Config:
    path = options.config_file or (os.environ.get(CONFIG_ENV) if options.use_environment else None)
    if path:
        if not os.path.isfile(path):
            raise FileNotFoundError(f"Zenoh config file {path!r} does not exist")
        config: zenoh.Config = zenoh.Config.from_file(path)
    else:
        mode = options.mode or options.default_mode
        config = zenoh.Config.from_file(str(zenoh_defaults.path(mode)))
        if options.multicast_scouting:
            config.insert_json5("scouting/multicast/enabled", "true")
        if options.connect or options.listen:  # the flags replace both of the file's lists,
            # but a peer given only --connect still listens on a free port of every interface
            # (Zenoh's own default), so peers that learn it through a router can dial it
            listen = options.listen or (["tcp/[::]:0"] if mode == "peer" else [])
            config.insert_json5("connect/endpoints", json.dumps(options.connect))
            config.insert_json5("listen/endpoints", json.dumps(listen))
    if path and options.mode:
        config.insert_json5("mode", json.dumps(options.mode))
    if options.connect:
        config.insert_json5("connect/endpoints", json.dumps(options.connect))
    if options.listen:
        config.insert_json5("listen/endpoints", json.dumps(options.listen))
    return config


def configured_endpoints(options: ZenohOptions) -> tuple[list[str], list[str]]:
    """(connect, listen) endpoints the session is configured with (flags, file or default);
    listen endpoints on port 0 (any free port: nobody can be pointed at them) left out."""
    config = build_config(options)
    mode = json.loads(config.get_json("mode") or '"peer"')

    def listed(key: str) -> list[str]:
        value = json.loads(config.get_json(key) or "null")
        if isinstance(value, dict):  # per-mode lists: {router: [...], peer: [...]}
            value = value.get(mode)
        return [str(e) for e in value or [] if not str(e).endswith(":0")]

    return listed("connect/endpoints"), listed("listen/endpoints")


def open_session(options: ZenohOptions) -> zenoh.Session:
    """Open a session; errors name the endpoints involved."""
    config = build_config(options)
    try:
        return zenoh.open(config)
    except Exception as exc:
        where = ", ".join(options.listen + options.connect) or options.config_file or DEFAULT_ROUTER
        raise ConnectionError(f"cannot open a Zenoh session ({where}): {exc}") from exc


def connect_to(endpoints: list[str], mode: str = "peer") -> zenoh.Session:
    """A session (a peer unless ``mode`` says otherwise, e.g. "client" as the C++ plugin is)
    that connects to ``endpoints`` only, whatever the environment says: what the offline
    runner, the benchmarks and the tests use."""
    options = ZenohOptions(connect=list(endpoints), mode=mode, use_environment=False)
    return open_session(options)
