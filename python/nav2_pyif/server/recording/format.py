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
    # files that end before their index: a host that did not end cleanly (SIGKILL, power
    # lost); what their complete chunks hold was read
    cut_short: list[Path] = field(default_factory=list)


def read_recording(paths: list[Path]) -> Recording:
    """Every call of ``paths`` (the files of one recording, rotated ones included, or of
    several runs of a host, in any order), ordered as the hosts took them: files by their
    first message's time, calls by sequence, a file's restore requests before its calls. A
    session restored in a file that an earlier file (given too) already built is not restored
    twice: the calls the earlier file recorded lead to that state."""
    files = sorted(_read_file(path) for path in paths)
    keys: dict[str, KeyInfo] = {}
    for file in files:
        for key, info in file.keys.items():
            known = keys.setdefault(key, info)
            known.plugin_type = info.plugin_type or known.plugin_type
            known.planner = info.planner or known.planner
    out: list[Call] = []
    seen: set[bytes] = set()  # sessions configured or restored so far
    for file in files:
        fresh = [r for r in file.restores if _sid(r.request) not in seen]
        for call in fresh + sorted(file.calls.values(), key=lambda c: c.sequence):
            if call.restore or call.op == "configure":
                seen.add(_sid(call.request))
            if call.request:
                out.append(call)
    reloads = sorted(r for file in files for r in file.reloads)
    return Recording(out, keys, reloads, [file.path for file in files if file.cut_short])


@dataclass(order=True)
class _File:
    start_ns: int  # its first message's log time: a later file of a run, or a later run
    path: Path
    calls: dict[int, Call] = field(compare=False)
    restores: list[Call] = field(compare=False)
    keys: dict[str, KeyInfo] = field(compare=False)
    reloads: list[tuple[int, str, str]] = field(compare=False)
    cut_short: bool = field(default=False, compare=False)


def _messages(path: Path) -> tuple[list[tuple[Any, Any]], bool]:
    """(channel, message) of every message of ``path``, and whether the file was cut short:
    then what its complete records hold, read one by one up to where it ends."""
    from mcap.exceptions import InvalidMagic
    from mcap.reader import make_reader
    from mcap.records import Channel, Message
    from mcap.stream_reader import StreamReader

    with open(path, "rb") as stream:
        try:
            read = make_reader(stream).iter_messages(log_time_order=False)
            return [(channel, message) for _schema, channel, message in read], False
        except Exception:  # no index (no footer), or a record cut in two
            stream.seek(0)
        found: list[tuple[Any, Any]] = []
        channels: dict[int, Any] = {}
        try:
            for record in StreamReader(stream).records:
                if isinstance(record, Channel):
                    channels[record.id] = record
                elif isinstance(record, Message) and record.channel_id in channels:
                    found.append((channels[record.channel_id], record))
        except InvalidMagic:
            raise  # not an MCAP file at all
        except Exception:
            pass  # where the file ends
        return found, True


def _read_file(path: Path) -> _File:
    messages, cut_short = _messages(path)
    file = _File(2**63, path, {}, [], {}, [], cut_short)
    for channel, message in messages:
        file.start_ns = min(file.start_ns, message.log_time)
        meta = channel.metadata
        key = meta.get("key", "")
        info = file.keys.setdefault(key, KeyInfo(key))
        info.plugin_type = meta.get("plugin_type", info.plugin_type)
        if "planner" in meta:
            info.planner = json.loads(meta["planner"])
        kind, data, seq = meta.get("kind", ""), message.data, message.sequence
        if kind == RESTORE:
            file.restores.append(Call(key, op_of(data), seq, data, message.log_time, restore=True))
        elif kind == RELOAD:
            file.reloads.append((message.log_time, key, data.decode()))
        elif kind in ("request", "reply"):
            call = file.calls.setdefault(seq, Call(key, meta["op"], seq, b"", 0))
            if kind == "request":
                call.request, call.received_ns = data, message.log_time
            else:
                call.reply, call.answered_ns = data, message.log_time
    return file


def _sid(payload: bytes) -> bytes:
    try:
        sid = msgpack.unpackb(payload).get("sid", "")
    except Exception:
        return b""
    return str(sid).encode()
