"""A bare Zenoh queryable replying an empty payload: the floor of any round trip.

python -m nav2_pyif_bench.bare_zenoh --listen tcp/127.0.0.1:7450 --key bench/bare

--callback answers in Zenoh's callback thread instead (`nav2-pyif-bench hops` compares the
two); --connect instead of --listen reaches the client through the session listening there
(the route a worker process's own queryable would take behind a host that listens).
"""

from __future__ import annotations

import argparse
import json
import signal
import threading
from typing import Any

import zenoh


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--listen")
    where.add_argument("--connect")
    parser.add_argument("--key", required=True)
    parser.add_argument("--callback", action="store_true")
    args = parser.parse_args()
    config = zenoh.Config()
    if args.listen:
        config.insert_json5("listen/endpoints", json.dumps([args.listen]))
    else:
        config.insert_json5("connect/endpoints", json.dumps([args.connect]))
    config.insert_json5("scouting/multicast/enabled", "false")
    session = zenoh.open(config)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())

    def answer(query: Any) -> None:
        query.reply(query.key_expr, b"")
        query.drop()

    queryable: Any
    if args.callback:
        queryable = session.declare_queryable(args.key, answer)
    else:
        # Same threading as the planner host: a FIFO channel read by one thread.
        queryable = session.declare_queryable(args.key, zenoh.handlers.FifoChannel(256))
        receiver = queryable.handler

        def serve() -> None:
            while True:
                try:
                    query: Any = receiver.recv()
                except Exception:
                    return
                answer(query)

        threading.Thread(target=serve, daemon=True).start()
    token = session.liveliness().declare_token(f"{args.key}/alive")
    print("ready", flush=True)
    stop.wait()
    token.undeclare()
    queryable.undeclare()
    session.close()


if __name__ == "__main__":
    main()
