"""``planner-host --record``: every call of the chosen keys to MCAP files (format.py).

The host's call threads only timestamp each call and queue its bytes (a few µs); a thread of
the recorder's own writes the files, a tenth of a second's calls at a time. What waits in that
queue is bounded: past ``max_queue_bytes`` (a disk that cannot keep up) calls are dropped from
the recording, counted and said in the log, never made to wait. A shadow journal per key, fed
with what was written, gives the restore requests each rotated file starts with
(server.journal), consistent with the calls written before it whatever the host did meanwhile.
"""

from __future__ import annotations

import json
import logging
import queue
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import msgpack

from nav2_pyif.server.journal import Journal
from nav2_pyif.server.recording.format import RELOAD, RESTORE, op_of, reply_topic, request_topic
from nav2_pyif.server.recording.writer import RotatingWriter

log = logging.getLogger("nav2_pyif.recording")

#: How long after a call's reply the recorder writes it (a host answers in well under that)
AFTER_REPLY_NS = 1_000_000
#: How long the recorder lets calls gather before it writes them
BATCH_S = 0.1
#: (key, op, request, reply, received unix ns, answered unix ns); a reload: op None, the label;
#: a session's state restored at a file's head: op RESTORE_ITEM
Item = tuple[str, str | None, bytes, bytes, int, int]
RESTORE_ITEM = ":restore"  # not an op name: ops are single key chunks without ':'
#: what a restore request is noted with in the shadow journal: the host accepted it
_ACCEPTED = msgpack.packb({"ok": True, "body": {}})


def take_batch(
    waiting: queue.SimpleQueue[Item | None], batch: list[Item]
) -> tuple[list[Item], bool]:
    """``batch`` and every item queued after it; whether the end (None) was among them."""
    while not waiting.empty():
        item = waiting.get()
        if item is None:
            return batch, True
        batch.append(item)
    return batch, False


@dataclass(frozen=True)
class RecordOptions:
    path: Path
    max_bytes: int = 100 * 2**20  # per file
    max_files: int = 10
    max_queue_bytes: int = 256 * 2**20
    # 0 for calls of another process (nav2-pyif record): no host thread here to wait for
    after_reply_ns: int = AFTER_REPLY_NS


class Recorder:
    def __init__(self, options: RecordOptions, key_metadata: dict[str, dict[str, str]]) -> None:
        self.options = options
        self._metadata = key_metadata  # per key: plugin_type, planner (JSON)
        self._queue: queue.SimpleQueue[Item | None] = queue.SimpleQueue()
        self._queued_bytes = 0  # updated unlocked by several threads: a bound, not an exact account
        self._sequence = 0
        self._sequence_lock = threading.Lock()
        self.dropped = 0
        self.written = 0
        self.cpu_ns = 0  # the writing thread's CPU time, known once closed
        self.keys = frozenset(key_metadata)
        self._journals = {key: Journal() for key in key_metadata}
        self._writer = RotatingWriter(
            options.path, options.max_bytes, options.max_files, self._channel_metadata
        )
        self._thread = threading.Thread(target=self._run, name="recorder", daemon=True)
        self._thread.start()
        log.info(
            "recording %s to %s (files of %d MB, the newest %d kept)",
            ", ".join(key_metadata),
            options.path,
            options.max_bytes // 2**20,
            options.max_files,
        )

    def _channel_metadata(self, key: str) -> dict[str, str]:
        return self._metadata.get(key, {})

    def add(self, key: str, op: str, request: bytes, reply: bytes, t0: int, t1: int) -> None:
        """On a host's call thread: queue one call, or count it dropped."""
        size = len(request) + len(reply)
        if self._queued_bytes + size > self.options.max_queue_bytes:
            self.dropped += 1
            if self.dropped == 1 or self.dropped % 1000 == 0:
                log.warning(
                    "recording: %d call(s) dropped, the disk does not keep up with %s",
                    self.dropped,
                    self.options.path,
                )
            return
        self._queued_bytes += size
        self._queue.put((key, op, request, reply, t0, t1))

    def reloaded(self, key: str, label: str) -> None:
        self._metadata.setdefault(key, {})["planner_label"] = label
        now = time.time_ns()
        self._queue.put((key, None, label.encode(), b"", now, now))

    def restore(self, key: str, requests: list[bytes]) -> None:
        """Requests that rebuild the sessions a live host had before this recording began
        (nav2-pyif record): written at the file's head, as a rotated file's are."""
        now = time.time_ns()
        for request in requests:
            self._queue.put((key, RESTORE_ITEM, request, b"", now, now))

    def _run(self) -> None:
        cpu = time.thread_time_ns()
        stopping = False
        while not stopping:
            first = self._queue.get()
            if first is None:
                break
            # One wake-up per batch, not per call: a thread's wake-up costs more CPU than
            # writing a call (measured: 100 µs per call woken each, 25 µs in batches).
            time.sleep(BATCH_S)
            batch, stopping = take_batch(self._queue, [first])
            for item in batch:
                self._write(item)
                time.sleep(0)  # lets a call thread that wants the GIL have it between two
        self.cpu_ns = time.thread_time_ns() - cpu

    def _write(self, item: Item) -> None:
        key, op, request, reply, t0, t1 = item
        # Write once the host has sent the reply: this thread holds the GIL while it writes,
        # and the call thread, wanting it back to reply, would wait for it.
        wait_ns = t1 + self.options.after_reply_ns - time.time_ns()
        if wait_ns > 0 and self.options.after_reply_ns:
            time.sleep(wait_ns / 1e9)
        writer = self._writer
        try:
            if op is None:
                writer.note(key, RELOAD, request, t0)
                return
            if op == RESTORE_ITEM:
                writer.note(key, RESTORE, request, t0)
                if key in self._journals:
                    self._journals[key].note(op_of(request), request, _ACCEPTED)
                return
            self._queued_bytes -= len(request) + len(reply)
            if writer.full:
                self._rotate()
            seq = self._sequence
            self._sequence += 1
            topic = request_topic(key, op)
            writer.write(writer.channel(key, topic, "request", op), request, t0, t0, seq)
            topic = reply_topic(key, op)
            writer.write(writer.channel(key, topic, "reply", op), reply, t1, t0, seq)
            self.written += 1
            if key in self._journals:
                self._journals[key].note(op, request, reply)
        except Exception:
            log.exception("recording: could not write a call of %s", key)

    def _rotate(self) -> None:
        self._writer.open_next()
        now = time.time_ns()
        for key, journal in self._journals.items():
            for _sid, (_version, requests) in journal.snapshot().items():
                for _op, payload in requests:
                    self._writer.note(key, RESTORE, payload, now)
        log.info("recording: now writing %s", self._writer.paths[-1])

    @property
    def paths(self) -> list[Path]:
        return list(self._writer.paths)

    def close(self) -> None:
        """Write what is queued, then the files' index; idempotent."""
        if not self._thread.is_alive():
            return
        self._queue.put(None)
        self._thread.join()
        totals = {"calls": self.written, "dropped": self.dropped}
        self._writer.metadata("nav2_pyif.recording", totals)
        self._writer.close()
        log.info(
            "recording: %d call(s) in %s%s; writing took %.1f µs of CPU per call",
            self.written,
            ", ".join(str(p) for p in self._writer.paths),
            f", {self.dropped} dropped" if self.dropped else "",
            self.cpu_ns / 1e3 / max(1, self.written),
        )


def key_metadata(plugin_type: str, spec: Any) -> dict[str, str]:
    """What a key's channels say about it: its plugin type and the planner served."""
    planner = {
        "planner": getattr(spec, "planner", None),
        "module": getattr(spec, "module", None),
        "delegates": dict(getattr(spec, "delegates", {}) or {}),
        "kind": getattr(spec, "kind", None),
    }
    return {"plugin_type": plugin_type, "planner": json.dumps(planner)}
