"""The recording's layout in MCAP, shared by the recorder and the replay.

Per served key ``P`` and op, two channels, named after the Zenoh keys the calls came on:
``P/rpc/<op>`` holds each request as it arrived (raw msgpack) and ``P/rpc/<op>/reply`` the
host's reply (raw msgpack, whose ``compute_ns`` is the planner's compute time). A request and
its reply share the message ``sequence``, a counter over the whole recording (every key, every
file), so the calls replay in the order the host took them. ``log_time``: when the host began
the call (request) and when it had the reply (reply), unix ns; ``publish_time`` of a reply is
its request's, so a reader sees the host's time per call without pairing.

``P/restore``: at the start of each file after the first, the requests that restore every
session live at that point (configure with the latest costmap, activate, the plan, the speed
limit: server.journal), so each rotated file replays on its own. ``P/reload``: a hot swap, the
new planner's label. Channel metadata names the key, its plugin type and the planner served.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import msgpack

ENCODING = "msgpack"  # the protocol's own bytes; PROTOCOL.md says what each holds
PROFILE = "nav2_pyif"  # the MCAP header's profile
LIBRARY = "nav2_pyif recorder"
REPLY_SUFFIX = "/reply"
RESTORE = "restore"
RELOAD = "reload"


def request_topic(key: str, op: str) -> str:
    return f"{key}/rpc/{op}"


def reply_topic(key: str, op: str) -> str:
    return request_topic(key, op) + REPLY_SUFFIX


def op_of(payload: bytes) -> str:
    """A request's op, read without validating the rest."""
    try:
        op = msgpack.unpackb(payload).get("op")
    except Exception:
        return "?"
    return op if isinstance(op, str) else "?"


@dataclass
class Call:
    """One recorded call of one key: its request, and its reply when it was recorded."""

    key: str
    op: str
    sequence: int
    request: bytes
    received_ns: int
    reply: bytes | None = None
    answered_ns: int = 0
    restore: bool = False  # a session's state restored at a file's start, not a real call


@dataclass
class KeyInfo:
    key: str
    plugin_type: str = ""
    planner: dict[str, Any] = field(default_factory=dict)  # PlannerSpec fields


@dataclass
class Recording:
    calls: list[Call]
    keys: dict[str, KeyInfo]
    reloads: list[tuple[int, str, str]]  # (unix ns, key, new planner label)


def read_recording(paths: list[Path]) -> Recording:
    """Every call of ``paths`` (the files of one recording, rotated ones included, any
    order), ordered as the host took them; a file's restore requests before its calls. A
    session restored in a later file that an earlier file (given too) already holds is not
    restored twice: the calls the earlier file recorded lead to that state."""
    from mcap.reader import make_reader

    calls: dict[int, Call] = {}
    restores: list[tuple[int, list[Call]]] = []  # (first sequence of the file, its restores)
    keys: dict[str, KeyInfo] = {}
    reloads: list[tuple[int, str, str]] = []
    for path in paths:
        first = None
        restoring: list[Call] = []
        with open(path, "rb") as stream:
            for _schema, channel, message in make_reader(stream).iter_messages(
                log_time_order=False
            ):
                meta = channel.metadata
                key = meta.get("key", "")
                info = keys.setdefault(key, KeyInfo(key))
                info.plugin_type = meta.get("plugin_type", info.plugin_type)
                if "planner" in meta:
                    info.planner = json.loads(meta["planner"])
                kind = meta.get("kind", "")
                if kind == RESTORE:
                    restoring.append(
                        Call(key, op_of(message.data), message.sequence, message.data,
                             message.log_time, restore=True)
                    )  # fmt: skip
                elif kind == RELOAD:
                    reloads.append((message.log_time, key, message.data.decode()))
                elif kind in ("request", "reply"):
                    call = calls.setdefault(
                        message.sequence, Call(key, meta["op"], message.sequence, b"", 0)
                    )
                    if kind == "request":
                        call.request, call.received_ns = message.data, message.log_time
                        first = message.sequence if first is None else min(first, message.sequence)
                    else:
                        call.reply, call.answered_ns = message.data, message.log_time
        if restoring:
            restores.append((first if first is not None else 2**63, restoring))
    ordered = sorted((c for c in calls.values() if c.request), key=lambda c: c.sequence)
    return Recording(_with_restores(ordered, restores), keys, sorted(reloads))


def _with_restores(calls: list[Call], restores: list[tuple[int, list[Call]]]) -> list[Call]:
    """Each file's restores just before its first call, kept only when nothing earlier in
    the recording (an earlier file read too: its calls or restores) built that session."""
    out: list[Call] = []
    pending = sorted(restores, key=lambda r: r[0])
    seen: set[bytes] = set()  # session ids the calls so far configured
    for call in [*calls, None]:
        while pending and (call is None or pending[0][0] <= call.sequence):
            _, restoring = pending.pop(0)
            fresh = [r for r in restoring if _sid(r.request) not in seen]
            seen.update(_sid(r.request) for r in fresh)
            out += fresh
        if call is not None:
            if call.op == "configure":
                seen.add(_sid(call.request))
            out.append(call)
    return out


def _sid(payload: bytes) -> bytes:
    try:
        sid = msgpack.unpackb(payload).get("sid", "")
    except Exception:
        return b""
    return str(sid).encode()


def iter_keys(recording: Recording) -> Iterator[str]:
    yield from sorted(recording.keys)
