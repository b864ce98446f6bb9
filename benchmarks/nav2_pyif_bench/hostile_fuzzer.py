"""A hostile peer: sends mutated requests (made from the shared vectors) to every key and op of
a live planner host, back to back, for a while, and sorts what comes back.

    python -m nav2_pyif_bench.hostile_fuzzer --connect tcp/127.0.0.1:7447 \\
        --key nav2_pyif/bench/FollowPath --seconds 60 --report out.json

Keys: ``<key>/rpc/<op>`` for every op (the host's plugin type serves only some), an op that
does not exist and the worker pipe's batch op, ``<key>/cancel``, ``<key>/admin/reload``,
``<key>/admin/info``, an admin verb that does not exist, and calls addressed to another
replica (``?host=...``). The report counts each outcome: a reply that decodes as the op's
(ok, or an error of a protocol type), an admin answer, no reply (the host dropped the query:
it counts those), and anything else (a contract broken: kept as examples).
"""

from __future__ import annotations

import argparse
import json
import random
import signal
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

from nav2_pyif.common.option_types import endpoint, positive_float, positive_int
from nav2_pyif.common.zenoh_config import connect_to
from nav2_pyif.server.batch_runtime import BATCH_OP
from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.codec import decode_reply
from nav2_pyif_protocol.constants import ErrorType, Op

from nav2_pyif_bench.mutations import load_seeds, mutate

TYPED = frozenset(e.value for e in ErrorType)
#: Seconds a reply may take: a call's is its host deadline at most (1 s for the control
#: loop's ops); what comes later counts as no reply.
REPLY_TIMEOUT = 5.0


def targets(prefix: str) -> list[tuple[str, str]]:
    """(outcome class, key expression) of every key and op the peer sends to."""
    calls = [("call", f"{prefix}/rpc/{op.value}") for op in Op if op is not Op.CANCEL_PLAN]
    return [
        *calls,
        ("call", f"{prefix}/rpc/no_such_op"),
        ("call", f"{prefix}/rpc/{BATCH_OP}"),
        ("cancel", f"{prefix}/cancel"),
        ("admin", f"{prefix}/admin/reload"),
        ("admin", f"{prefix}/admin/info"),
        ("dropped", f"{prefix}/admin/no_such_verb"),
        ("dropped", f"{prefix}/rpc/compute_velocity_commands?host=another-replica"),
    ]


class Tally:
    def __init__(self) -> None:
        self.outcomes: Counter[str] = Counter()
        self.error_types: Counter[str] = Counter()
        self.broken: list[str] = []
        self.sent = 0
        self.slowest: list[tuple[float, str, str]] = []  # (ms, key, the vector mutated)

    def timed(self, ms: float, key: str, seed: str) -> None:
        """Keep the five slowest queries: what a hostile peer can make the host spend."""
        self.slowest = sorted([*self.slowest, (ms, key, seed)], reverse=True)[:5]

    def sort(self, kind: str, key: str, replies: list[bytes]) -> None:
        self.sent += 1
        if not replies:
            self.outcomes["no reply"] += 1
            if kind != "dropped":
                self._broke(f"{key}: no reply")
            return
        if kind == "dropped":
            self._broke(f"{key}: answered a query the host should drop")
        for reply in replies:
            self._sort_one(kind, key, reply)

    def _sort_one(self, kind: str, key: str, reply: bytes) -> None:
        if kind == "admin":
            answer = unpack_bounded(reply)
            if isinstance(answer, dict):
                self.outcomes["admin answer"] += 1
            else:
                self._broke(f"{key}: admin answer {reply[:80]!r}")
            return
        op = Op.CANCEL_PLAN if kind == "cancel" else _op_of(key)
        try:
            decoded = decode_reply(reply, op)
        except Exception as exc:
            self._broke(f"{key}: undecodable reply {reply[:80]!r}: {exc}")
            return
        if decoded.ok:
            self.outcomes["ok reply"] += 1
        elif decoded.error is not None and decoded.error.type in TYPED:
            self.outcomes["typed error"] += 1
            self.error_types[decoded.error.type] += 1
        else:
            self._broke(f"{key}: untyped error {decoded.error}")

    def _broke(self, what: str) -> None:
        self.outcomes["contract broken"] += 1
        if len(self.broken) < 20:
            self.broken.append(what)

    def report(self, seconds: float) -> dict[str, Any]:
        return {
            "sent": self.sent,
            "seconds": seconds,
            "rate_hz": self.sent / seconds if seconds else 0.0,
            "outcomes": dict(self.outcomes),
            "error_types": dict(self.error_types),
            "broken": self.broken,
            "slowest": [f"{ms:.0f} ms: {key} <- {seed} mutated" for ms, key, seed in self.slowest],
        }


def _op_of(key: str) -> Op:
    """The op a call key names; another (no_such_op, the batch op) reads as activate's,
    whose error replies are the same."""
    name = key.split("?")[0].rsplit("/", 1)[1]
    try:
        return Op(name)
    except ValueError:
        return Op.ACTIVATE


def _ask(session: Any, key: str, payload: bytes) -> list[bytes]:
    replies = session.get(key, payload=payload, timeout=REPLY_TIMEOUT)
    return [r.ok.payload.to_bytes() for r in replies if r.ok is not None]


def run(connect: str, prefix: str, seconds: float, seed: int, only: str = "") -> dict[str, Any]:
    rng = random.Random(seed)
    seeds = [(name, data) for name, (_, data) in load_seeds("request").items()]
    keys = [target for target in targets(prefix) if only in target[1]]
    if not keys:
        raise ValueError(f"no key of {prefix} contains {only!r}")
    tally = Tally()
    session = connect_to([connect], "client")
    started = time.monotonic()
    try:
        while time.monotonic() - started < seconds:
            kind, key = rng.choice(keys)
            name, data = rng.choice(seeds)
            asked = time.monotonic()
            replies = _ask(session, key, mutate(rng, data))
            tally.timed(1000 * (time.monotonic() - asked), key, name)
            tally.sort(kind, key, replies)
    finally:
        session.close()
    return tally.report(time.monotonic() - started)


def send_seeds(connect: str, prefix: str) -> dict[str, Any]:
    """Every vector once, unchanged, on its op's key: the traffic a host is made for, which
    imports what serving it needs (a message type's module) before the hostile part."""
    tally = Tally()
    session = connect_to([connect], "client")
    started = time.monotonic()
    try:
        # cleanup last: it ends the vectors' session, which the others' calls need
        for op, data in sorted(load_seeds("request").values(), key=lambda s: s[0] == "cleanup"):
            kind = "cancel" if op == Op.CANCEL_PLAN.value else "call"
            key = f"{prefix}/cancel" if kind == "cancel" else f"{prefix}/rpc/{op}"
            tally.sort(kind, key, _ask(session, key, data))
    finally:
        session.close()
    return tally.report(time.monotonic() - started)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m nav2_pyif_bench.hostile_fuzzer",
        description="Send mutated requests to every key and op of a live planner host.",
    )
    parser.add_argument("--connect", type=endpoint, required=True, help="the host's endpoint")
    parser.add_argument("--key", required=True, help="the key prefix the host serves")
    parser.add_argument(
        "--seconds", type=positive_float, default=60.0, help="how long (default 60)"
    )
    parser.add_argument("--seed", type=positive_int, default=1, help="of the mutations (default 1)")
    parser.add_argument("--report", type=Path, help="write the counts here as JSON")
    parser.add_argument(
        "--only", default="", metavar="TEXT", help="send only to the keys that contain TEXT"
    )
    parser.add_argument(
        "--seeds-only", action="store_true", help="send every vector once, unchanged, and stop"
    )
    args = parser.parse_args(argv)

    def interrupted(signum: int, frame: object) -> None:
        raise SystemExit(128 + signum)  # the session is closed on the way out

    signal.signal(signal.SIGTERM, interrupted)
    try:
        if args.seeds_only:
            report = send_seeds(args.connect, args.key)
        else:
            report = run(args.connect, args.key, args.seconds, args.seed, args.only)
    except KeyboardInterrupt:
        return 130
    text = json.dumps(report, indent=1)
    if args.report:
        args.report.write_text(text)
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
