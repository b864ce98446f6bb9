"""What one more hop on the control cycle's path costs, by kind of hop:

- ``pipe``: two Python processes echoing a 300-byte request over a multiprocessing pipe — the
  host ↔ worker hop that crash isolation adds to every call;
- ``channel``: a Zenoh get answered by a queryable read from a FIFO channel by a Python thread
  (how the planner host and the bare floor answer), ``callback``: answered in Zenoh's own
  callback thread instead;
- ``relayed``: the same get answered by a queryable in a second process that reaches the
  client through a first process's listening session — the route a worker's own Zenoh
  queryable would take behind a host the plugin connects to. The client is in client mode,
  as the C++ plugin's zenoh-pico is (and as every other row's client); ``gossip``: the same
  with a peer client, which learns the second process's own endpoint and connects to it;
- behind a Zenoh router (the default deployment: the host a peer of the router, the plugin a
  client of it; ``routed_peer`` has the two serving processes): ``routed``, a queryable
  replying in its own process (the cycle with the planner in the host, or a worker owning
  the call path with no supervisor watching); ``routed_pipe``, the host's queryable relaying
  through the call pipe to a worker process (today's crash isolation); ``routed_guard``, the
  worker's own queryable replying while the host's queryable holds each query until the
  worker's done-notice (the worker owning the call path, with the supervisor still able to
  answer a query the worker dies on), the client asking with consolidation NONE and taking
  the first reply.

Each in a tight loop and at a real control rate (rows spread over the period), with a
300-byte request like compute_velocity_commands'.
"""

from __future__ import annotations

import argparse
import multiprocessing
import time
from collections.abc import Callable
from dataclasses import asdict
from multiprocessing.connection import Connection
from typing import Any

import zenoh
from nav2_pyif.common.zenoh_config import connect_to
from nav2_pyif.server.frames import FramedPipe

from nav2_pyif_bench.processes import free_port, peer_processes
from nav2_pyif_bench.protocol_bench import add_rounds_and_rate, interleaved, paced, progress
from nav2_pyif_bench.stats import Summary, header_row

REQUEST = b"r" * 300
ROWS = {
    "pipe": "pipe to a worker process and back (FramedPipe)",
    "connection": "  the same, multiprocessing.Connection both ends",
    "channel": "Zenoh get -> FIFO-channel queryable (the host's way)",
    "callback": "Zenoh get -> callback queryable",
    "relayed": "Zenoh get -> queryable behind a listening peer",
    "gossip": "  the same from a peer client (direct by gossip)",
    "routed": "router -> queryable replying in its own process",
    "routed_pipe": "router -> host -> pipe -> worker (today's isolation)",
    "routed_guard": "router -> worker's own queryable, host guarding",
}


ROUTED = ("routed", "routed_pipe", "routed_guard")


def _echo(conn: Connection, framed: bool) -> None:
    end: Any = FramedPipe(conn) if framed else conn
    receive, send = (end.recv, end.send) if framed else (end.recv_bytes, end.send_bytes)
    while message := receive():
        send(message)


class PipeEcho:
    """A worker process echoing over a pipe: framed as the host's call pipe (FramedPipe), or
    with multiprocessing.Connection's own framing (what the host used before)."""

    def __init__(self, framed: bool) -> None:
        context = multiprocessing.get_context("spawn")  # as the host starts its workers
        conn, child = context.Pipe()
        self.process = context.Process(target=_echo, args=(child, framed), daemon=True)
        self.process.start()
        child.close()
        self.end: Any = FramedPipe(conn) if framed else conn
        self.send = self.end.send if framed else conn.send_bytes
        self.receive = self.end.recv if framed else conn.recv_bytes

    def __call__(self) -> int:
        start = time.perf_counter_ns()
        self.send(REQUEST)
        self.receive()
        return time.perf_counter_ns() - start

    def close(self) -> None:
        self.send(b"")
        self.process.join(5)


def _bare(key: str, *where: str) -> list[str]:
    return ["-m", "nav2_pyif_bench.bare_zenoh", "--key", key, *where]


def _open(endpoint: str, mode: str, wait: float = 30.0) -> zenoh.Session:
    """A session to a peer process that may still be starting."""
    end = time.monotonic() + wait
    while True:
        try:
            return connect_to([endpoint], mode=mode)
        except ConnectionError:
            if time.monotonic() > end:
                raise
            time.sleep(0.2)


def _timed_get(session: zenoh.Session, key: str) -> int:
    """Round trip [ns] of one get until its first reply (consolidation NONE, every
    queryable asked, as a guarded worker needs); raises TimeoutError unless a reply came."""
    start = time.perf_counter_ns()
    replies = session.get(
        key,
        payload=REQUEST,
        timeout=2.0,
        target=zenoh.QueryTarget.ALL,
        consolidation=zenoh.ConsolidationMode.NONE,
    )
    for reply in replies:
        if reply.ok is not None:
            return time.perf_counter_ns() - start
    raise TimeoutError(f"nothing answered {key}")


def _answered(session: zenoh.Session, key: str, wait: float = 30.0) -> Callable[[], int]:
    end = time.monotonic() + wait
    while True:
        try:
            _timed_get(session, key)
            return lambda: _timed_get(session, key)
        except TimeoutError:
            if time.monotonic() > end:
                raise
            time.sleep(0.2)


def run(args: argparse.Namespace) -> dict[str, Any]:
    channel, callback, relay, router = (f"tcp/127.0.0.1:{free_port()}" for _ in range(4))
    routed = ["-m", "nav2_pyif_bench.routed_peer", "--connect", router]
    peers = {
        "router": ["-m", "nav2_pyif.tools.main", "router", "--listen", router],
        "channel": _bare("hop/channel", "--listen", channel),
        "callback": _bare("hop/callback", "--listen", callback, "--callback"),
        "relay": _bare("hop/relay", "--listen", relay),
        "relayed": _bare("hop/relayed", "--connect", relay),
        "routed": _bare("hop/routed", "--connect", router),
        "routed_pipe": [*routed, "--key", "hop/routed_pipe", "--way", "pipe"],
        "routed_guard": [*routed, "--key", "hop/routed_guard", "--way", "guard"],
    }
    pipe, connection = PipeEcho(framed=True), PipeEcho(framed=False)
    sessions: list[zenoh.Session] = []
    try:
        with peer_processes(peers, {}):
            progress("waiting for the queryables")
            # Client mode, as the C++ plugin's zenoh-pico; the last one a peer.
            for endpoint, mode in ((channel, "client"), (callback, "client"), (relay, "client")):
                sessions.append(_open(endpoint, mode))
            sessions.append(_open(relay, "peer"))
            sessions.append(_open(router, "client"))
            rows: dict[str, Callable[[], int]] = {
                "pipe": pipe,
                "connection": connection,
                "channel": _answered(sessions[0], "hop/channel"),
                "callback": _answered(sessions[1], "hop/callback"),
                "relayed": _answered(sessions[2], "hop/relayed"),
                "gossip": _answered(sessions[3], "hop/relayed"),
                **{k: _answered(sessions[4], f"hop/{k}") for k in ROUTED},
            }
            tight = interleaved(rows, args.rounds, args.calls, "tight loop")
            at_rate = paced(rows, args.paced_calls, args.rate)
    finally:
        pipe.close()
        connection.close()
        for session in sessions:
            session.close()
    return {
        "rate": args.rate,
        "tight": {k: asdict(Summary.of_ns(v)) for k, v in tight.items()},
        "paced": {k: asdict(Summary.of_ns(v)) for k, v in at_rate.items()},
    }


def report(results: dict[str, Any]) -> str:
    lines = ["one hop, 300-byte request (tight loop)", header_row(52)]
    for part, title in (("tight", None), ("paced", f"at {results['rate']:g} Hz")):
        if title:
            lines += [f"one hop, 300-byte request ({title})", header_row(52)]
        lines += [Summary(**results[part][k]).row(label, 52) for k, label in ROWS.items()]
    t = {k: Summary(**v) for k, v in results["tight"].items()}
    p = {k: Summary(**v) for k, v in results["paced"].items()}
    lines += [
        "  a worker's own queryable behind a listening host adds (relayed - channel): "
        f"{t['relayed'].median_us - t['channel'].median_us:+.1f} µs median tight, "
        f"{p['relayed'].median_us - p['channel'].median_us:+.1f} µs at the rate; the pipe "
        f"hop it would replace: {t['pipe'].median_us:.1f} / {p['pipe'].median_us:.1f} µs",
        "  behind a router, against today's isolation (routed_pipe): a worker owning the call "
        f"path guarded {_ratio(t, 'routed_guard')} tight, {_ratio(p, 'routed_guard')} at the "
        f"rate; unguarded {_ratio(t, 'routed')} tight, {_ratio(p, 'routed')} at the rate",
    ]
    return "\n".join(lines)


def _ratio(rows: dict[str, Summary], name: str) -> str:
    """``name``'s median and p99 as fractions of routed_pipe's."""
    base, row = rows["routed_pipe"], rows[name]
    return f"{row.median_us / base.median_us:.2f}x median, {row.p99_us / base.p99_us:.2f}x p99"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_rounds_and_rate(parser, paced_calls=200, none_paced=False)


def apply_quick(args: argparse.Namespace) -> argparse.Namespace:
    if args.quick:
        args.rounds, args.calls, args.paced_calls = 2, 50, 10
    return args
