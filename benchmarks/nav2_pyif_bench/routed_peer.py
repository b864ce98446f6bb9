"""A planner host's two ways of crash isolation, stripped to their hops, behind a Zenoh router
(the default deployment: the host is a peer of the router, the plugin a client of it).

python -m nav2_pyif_bench.routed_peer --connect tcp/127.0.0.1:7447 --key bench/k --way pipe

- ``pipe`` (today's): the host's queryable hands each request to a worker process over the
  call pipe (``FramedPipe``) and replies with what comes back;
- ``guard`` ("the worker owns the call path"): the worker has its own session
  and queryable and replies itself, then posts a one-way done-notice on the pipe; the host's
  queryable on the same key receives every query too and holds it until that notice, so that
  it could answer Unavailable or TimedOut if the worker died or overran (the fault suite's
  semantics). Clients must then ask with consolidation NONE and take the first reply.

Replies are the empty payload, as the bare floor's: only the hops are measured.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import multiprocessing
import os
import signal
import threading
from multiprocessing.connection import Connection
from typing import Any

import zenoh
from nav2_pyif.common.zenoh_config import connect_to
from nav2_pyif.server.frames import FramedPipe


def _echo_worker(conn: Connection) -> None:
    pipe = FramedPipe(conn)
    with contextlib.suppress(EOFError, OSError):  # the host is gone: so is its worker
        while message := pipe.recv():
            pipe.send(message[:0])


def _exit_with_the_host(pipe: FramedPipe) -> None:
    """The host never writes to its owning worker: a read ends only when the host is gone
    (even by SIGKILL, which leaves it no time to stop its children)."""
    with contextlib.suppress(EOFError, OSError):
        pipe.recv()
    os._exit(0)


def _owning_worker(conn: Connection, endpoint: str, key: str) -> None:
    """The worker's own queryable: reply, then tell the guard the query is done."""
    pipe = FramedPipe(conn)
    threading.Thread(target=_exit_with_the_host, args=(pipe,), daemon=True).start()
    session = connect_to([endpoint], mode="peer")
    queryable = session.declare_queryable(key, zenoh.handlers.FifoChannel(256))
    pipe.send(b"ready")
    while True:
        try:
            query: Any = queryable.handler.recv()
        except Exception:
            return
        query.reply(query.key_expr, b"")
        query.drop()
        pipe.send(b"done")


def _spawn(target: Any, *args: Any) -> tuple[FramedPipe, Any]:
    context = multiprocessing.get_context("spawn")  # as the host starts its workers
    conn, child = context.Pipe()
    process = context.Process(target=target, args=(child, *args), daemon=True)
    process.start()
    child.close()
    return FramedPipe(conn), process


def serve_through_pipe(session: zenoh.Session, key: str) -> Any:
    pipe, _ = _spawn(_echo_worker)
    queryable = session.declare_queryable(key, zenoh.handlers.FifoChannel(256))

    def serve() -> None:
        while True:
            try:
                query: Any = queryable.handler.recv()
            except Exception:
                return
            pipe.send(bytes(query.payload) if query.payload is not None else b"")
            query.reply(query.key_expr, pipe.recv())
            query.drop()

    threading.Thread(target=serve, daemon=True).start()
    return queryable


def serve_guarded(session: zenoh.Session, endpoint: str, key: str) -> Any:
    pipe, _ = _spawn(_owning_worker, endpoint, key)
    if pipe.recv() != b"ready":
        raise RuntimeError("the worker did not start")
    held: collections.deque[Any] = collections.deque()
    lock = threading.Lock()
    notices = 0  # done-notices that came before their query reached the guard

    def hold(query: Any) -> None:
        nonlocal notices
        with lock:
            if notices:
                notices -= 1
                query.drop()
            else:
                held.append(query)

    def release() -> None:
        nonlocal notices
        while True:
            try:
                pipe.recv()
            except EOFError:
                return
            with lock:
                if held:
                    held.popleft().drop()
                else:
                    notices += 1

    threading.Thread(target=release, daemon=True).start()
    return session.declare_queryable(key, hold)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--connect", required=True, help="the router's endpoint")
    parser.add_argument("--key", required=True)
    parser.add_argument("--way", choices=["pipe", "guard"], required=True)
    args = parser.parse_args()
    session = connect_to([args.connect], mode="peer")
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    if args.way == "pipe":
        queryable = serve_through_pipe(session, args.key)
    else:
        queryable = serve_guarded(session, args.connect, args.key)
    print("ready", flush=True)
    stop.wait()
    queryable.undeclare()
    session.close()


if __name__ == "__main__":
    main()
