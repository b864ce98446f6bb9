"""How the command-line tools (``nav2-pyif reload``, ``sim --connect``, ``hosts``) join the
Zenoh network, and what they say when they reach nothing.

A tool is a client (as the C++ plugin is) unless told otherwise. A client that finds no
router at its endpoint fails to open; a tool started right after ``nav2-pyif router`` (a
script, or the README's sequence typed quickly) would then fail for nothing, so a tool may
wait for its router up to its own patience, saying that it waits."""

from __future__ import annotations

import json
import sys
import threading

import zenoh

from nav2_pyif.common.zenoh_config import ZenohOptions, build_config, configured_endpoints

#: After this long without a router (or host), a tool says what it is waiting for.
SAY_AFTER = 3.0


def unreachable(options: ZenohOptions) -> str:
    """What a tool that reached no router or peer at all tells the user: where it tried."""
    connect, listen = configured_endpoints(options)
    tried = ", ".join(connect) or "no connect endpoint"
    return (
        f"reached no Zenoh router or peer at all (tried {tried}"
        + (f"; listening on {', '.join(listen)}" if listen else "")
        + "): start a router there (zenohd, or nav2-pyif router), or --connect to where "
        "the planner hosts are"
    )


def open_tool_session(options: ZenohOptions, tool: str, patience: float = 0.0) -> zenoh.Session:
    """The tool's session. In client mode, wait up to ``patience`` seconds for a router at
    the connect endpoints (saying so on stderr after SAY_AFTER s); raises ConnectionError
    naming the endpoints tried when none answers. A peer opens at once and keeps trying."""
    config = build_config(options)
    client = json.loads(config.get_json("mode") or '"peer"') == "client"
    if client and patience > 0:
        config.insert_json5("connect/timeout_ms", str(round(patience * 1000)))
    note = threading.Timer(
        SAY_AFTER,
        lambda: print(
            f"{tool}: no Zenoh router answers yet at "
            f"{', '.join(configured_endpoints(options)[0]) or '?'}; waiting up to "
            f"{patience:g} s",
            file=sys.stderr,
            flush=True,
        ),
    )
    note.daemon = True
    if client and patience > SAY_AFTER:
        note.start()
    try:
        return zenoh.open(config)
    except Exception as exc:
        raise ConnectionError(unreachable(options)) from exc
    finally:
        note.cancel()
