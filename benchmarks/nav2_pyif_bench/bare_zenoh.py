"""A bare Zenoh queryable replying an empty payload: the floor of any round trip.

python -m nav2_pyif_bench.bare_zenoh --listen tcp/127.0.0.1:7450 --key bench/bare
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
    parser.add_argument("--listen", required=True)
    parser.add_argument("--key", required=True)
    args = parser.parse_args()
    config = zenoh.Config()
    config.insert_json5("listen/endpoints", json.dumps([args.listen]))
    config.insert_json5("scouting/multicast/enabled", "false")
    session = zenoh.open(config)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    # Same threading as the planner host: a FIFO channel read by one thread.
    queryable = session.declare_queryable(args.key, zenoh.handlers.FifoChannel(256))
    receiver = queryable.handler

    def serve() -> None:
        while True:
            try:
                query: Any = receiver.recv()
            except Exception:
                return
            query.reply(query.key_expr, b"")
            query.drop()

    threading.Thread(target=serve, daemon=True).start()
    token = session.liveliness().declare_token(f"{args.key}/alive")
    print("ready", flush=True)
    stop.wait()
    token.undeclare()
    queryable.undeclare()
    session.close()


if __name__ == "__main__":
    main()
