"""An empty-reply queryable answered from a second process, the two ways crash isolation
could cross into a worker (issue 15): a Zenoh session of the worker's own, connected to the
host's session (the worker owns the call path; the host's session routes each query to it),
or the host's queryable handing each query to the worker over a pipe (what the supervisor
does). Compared with the bare queryable (``bare_zenoh``) by ``nav2-pyif-bench isolation-hop``.

python -m nav2_pyif_bench.hop_peer --listen tcp/127.0.0.1:7450 --key bench/hop --via session
"""

from __future__ import annotations

import argparse
import multiprocessing
import signal
import threading
from multiprocessing.connection import Connection
from typing import Any

import zenoh
from nav2_pyif.frames import FramedPipe
from nav2_pyif.zenoh_config import ZenohOptions, connect_to, open_session

_SPAWN = multiprocessing.get_context("spawn")


def _answer_empty(queryable: Any, forward: FramedPipe | None = None) -> None:
    """As the planner host: a FIFO channel read by one thread; the reply is empty, or what
    the worker answers through ``forward``."""
    receiver = queryable.handler
    while True:
        try:
            query: Any = receiver.recv()
        except Exception:
            return
        if forward is not None:
            forward.send(query.payload.to_bytes() if query.payload is not None else b"")
        query.reply(query.key_expr, forward.recv() if forward is not None else b"")
        query.drop()


def _session_worker(endpoint: str, key: str, ready: Any) -> None:
    session = connect_to([endpoint])
    queryable = session.declare_queryable(key, zenoh.handlers.FifoChannel(256))
    ready.set()
    _answer_empty(queryable)


def _pipe_worker(connection: Connection) -> None:
    pipe = FramedPipe(connection)
    while True:
        try:
            pipe.recv()
        except EOFError:
            return
        pipe.send(b"")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--listen", required=True)
    parser.add_argument("--key", required=True)
    parser.add_argument("--via", choices=["session", "pipe"], required=True)
    args = parser.parse_args()
    session = _listening(args.listen)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    if args.via == "session":
        ready = _SPAWN.Event()
        worker = _SPAWN.Process(
            target=_session_worker, args=(args.listen, args.key, ready), daemon=True
        )
        worker.start()
        ready.wait(30)
    else:
        ours, theirs = _SPAWN.Pipe()
        worker = _SPAWN.Process(target=_pipe_worker, args=(theirs,), daemon=True)
        worker.start()
        queryable = session.declare_queryable(args.key, zenoh.handlers.FifoChannel(256))
        threading.Thread(
            target=_answer_empty, args=(queryable, FramedPipe(ours)), daemon=True
        ).start()
    print("ready", flush=True)
    stop.wait()
    worker.kill()
    session.close()


def _listening(endpoint: str) -> zenoh.Session:
    """A peer listening where the C++ client connects, configured as the planner host is."""
    return open_session(ZenohOptions(listen=[endpoint], use_environment=False))


if __name__ == "__main__":
    main()
