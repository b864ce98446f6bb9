"""Checked types for command-line options (argparse ``type=``), shared by every command.

A bad value is a usage error (exit 2) before anything starts, naming the option (argparse
prefixes "argument --deadline: ") or, through ``env_defaults``, the NAV2_PYIF_* variable,
and the accepted range or form. Numbers are finite: ``nan`` and ``inf`` parse as floats
but mean nothing as a deadline or a rate.
"""

from __future__ import annotations

import argparse
import math
import os
import re
from collections.abc import Callable
from typing import TypeVar

N = TypeVar("N", int, float)


def number(
    kind: Callable[[str], N],
    *,
    above: float | None = None,
    at_least: float | None = None,
    at_most: float | None = None,
) -> Callable[[str], N]:
    """A finite ``kind`` (int or float) in the range given; the error names the range."""
    bounds = {">": above, ">=": at_least, "<=": at_most}
    rule = " and ".join(f"{op} {v:g}" for op, v in bounds.items() if v is not None)
    expected = f"{'an integer' if kind is int else 'a number'} {rule}".strip()

    def convert(text: str) -> N:
        try:
            value = kind(text)
        except (TypeError, ValueError):
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}") from None
        if not (
            math.isfinite(value)
            and (above is None or value > above)
            and (at_least is None or value >= at_least)
            and (at_most is None or value <= at_most)
        ):
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}")
        return value

    convert.__name__ = f"{getattr(kind, '__name__', 'number')} {rule}".strip()
    return convert


finite_float = number(float)
positive_float = number(float, above=0)
non_negative_float = number(float, at_least=0)
positive_int = number(int, at_least=1)
non_negative_int = number(int, at_least=0)

#: Zenoh's link protocols (zenoh-link: each a feature of the build; eclipse-zenoh's wheels
#: carry the common ones). Those taking HOST:PORT are checked further.
IP_PROTOCOLS = ("tcp", "udp", "tls", "quic", "ws")
OTHER_PROTOCOLS = ("unixsock-stream", "unixpipe", "serial", "vsock")
ENDPOINT_FORM = "PROTOCOL/ADDRESS, e.g. tcp/HOST:PORT (tcp/127.0.0.1:7447)"
_HOST_PORT = re.compile(r"^(\[[0-9A-Fa-f:.%\w]+\]|[^\s:/\[\]]+):(\d{1,5})$")


def endpoint(text: str) -> str:
    """A Zenoh endpoint, ``<protocol>/<address>[?<metadata>][#<config>]``; for the IP
    protocols the address is HOST:PORT (an IPv6 host in brackets)."""
    protocol, slash, rest = text.strip().partition("/")
    address = re.split(r"[?#]", rest, maxsplit=1)[0]
    if not slash or not protocol or not address:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a Zenoh endpoint: expected {ENDPOINT_FORM}"
        )
    if protocol not in IP_PROTOCOLS + OTHER_PROTOCOLS:
        known = ", ".join(IP_PROTOCOLS + OTHER_PROTOCOLS)
        raise argparse.ArgumentTypeError(
            f"{text!r}: unknown Zenoh protocol {protocol!r} (one of {known}); expected "
            f"{ENDPOINT_FORM}"
        )
    if protocol in IP_PROTOCOLS:
        match = _HOST_PORT.match(address)
        if match is None or int(match.group(2)) > 65535:
            raise argparse.ArgumentTypeError(
                f"{text!r}: expected {protocol}/HOST:PORT with a port in 0-65535, e.g. "
                f"{protocol}/127.0.0.1:7447 or {protocol}/[::1]:7447"
            )
    return text.strip()


class FromVariable(str):
    """An option's default taken from an environment variable: a type's error names it."""

    variable: str

    def __new__(cls, value: str, variable: str) -> FromVariable:
        made = super().__new__(cls, value)
        made.variable = variable
        return made


def zenoh_config_file(text: str) -> str:
    """A Zenoh JSON5 config file that exists and that Zenoh can read (its endpoints
    included): checked before any worker or session starts."""
    import zenoh

    given = f"${text.variable}={str(text)!r}: " if isinstance(text, FromVariable) else ""
    if not os.path.isfile(text):
        raise argparse.ArgumentTypeError(f"{given}Zenoh config file {text!r} does not exist")
    try:
        zenoh.Config.from_file(text)
    except Exception as exc:  # zenoh.ZError: a JSON5 or endpoint error, with Rust's location
        reason = re.sub(r" at /\S+:\d+\.?", "", str(exc)).strip()
        raise argparse.ArgumentTypeError(f"{given}Zenoh cannot read {text!r}: {reason}") from None
    return str(text)


def add_path_argument(parser: argparse.ArgumentParser) -> None:
    """``--path DIR``: where the tools that load planners (sim, replay) import them from."""
    parser.add_argument(
        "--path",
        action="append",
        default=[],
        metavar="DIR",
        help="directory to import planners from, repeatable (the current directory is "
        "always searched)",
    )


def add_pose_arguments(parser: argparse.ArgumentParser, when: str) -> None:
    """``--start X Y YAW`` and ``--goal X Y YAW`` of the tools that drive a robot (sim, eval);
    ``when`` says when they apply."""
    for name in ("start", "goal"):
        parser.add_argument(
            f"--{name}",
            nargs=3,
            type=finite_float,
            metavar=("X", "Y", "YAW"),
            help=f"{name} pose [m, m, rad] ({when})",
        )
