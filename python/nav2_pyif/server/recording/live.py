"""``nav2-pyif record`` on the host's side: a copy of each call of a key, streamed to a recorder.

Off unless the host runs with ``--allow-live-record``; a host without it refuses every start.
A recorder asks on ``P/admin/record`` (PROTOCOL.md section 1) with a stream id and a lease:
``start`` declares a publisher on ``P/record/<id>``, ``renew`` extends the lease, ``stop``
ends it. A stream whose lease runs out (a recorder killed, its link gone) is ended by the
host, so nothing is streamed to nobody. The call threads only look up whether their key
streams (a dict lookup while none does) and queue the call; this class's thread publishes,
a batch at a time, each item msgpack ``[op, request, reply, received ns, answered ns]`` (op
nil: a hot swap, the request its label).
"""

from __future__ import annotations

import contextlib
import logging
import queue
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import msgpack
import zenoh
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.server.recording.recorder import Item, take_batch

log = logging.getLogger("nav2_pyif.recording")

#: The longest lease a recorder may ask for: a killed one stops the stream within it
MAX_LEASE_S = 30.0
#: How long the publishing thread lets calls gather before it publishes them
BATCH_S = 0.05
#: What may wait to be streamed; past it (a recorder that cannot keep up) calls are dropped
MAX_QUEUE_BYTES = 64 * 2**20

OFF = (
    "live recording is off on this host (start planner-host with --allow-live-record; "
    "--record FILE.mcap records on the host's own disk)"
)


@dataclass
class _Stream:
    key: str
    stream_id: str
    publisher: Any
    expires: float  # time.monotonic()


class LiveTap:
    """The recorder interface of server.recording.service (``keys``, ``add``, ``reloaded``)
    for every served key, streaming only while a recorder holds a lease on it."""

    def __init__(self, session: zenoh.Session, key_metadata: dict[str, dict[str, str]]) -> None:
        self.session = session
        self.keys = frozenset(key_metadata)
        self._metadata = key_metadata
        self._streams: dict[str, list[_Stream]] = {}  # key -> its live streams
        self._lock = threading.Lock()
        self._queue: queue.SimpleQueue[Item | None] = queue.SimpleQueue()
        self._queued_bytes = 0
        self.dropped = 0
        self._thread = threading.Thread(target=self._run, name="live-record", daemon=True)
        self._thread.start()

    def add(self, key: str, op: str, request: bytes, reply: bytes, t0: int, t1: int) -> None:
        if key not in self._streams:  # read without the lock: at worst one call early or late
            return
        size = len(request) + len(reply)
        if self._queued_bytes + size > MAX_QUEUE_BYTES:
            self.dropped += 1
            if self.dropped == 1 or self.dropped % 1000 == 0:
                log.warning("live recording: %d call(s) dropped, a recorder lags", self.dropped)
            return
        self._queued_bytes += size  # unlocked, as the recorder's: a bound, not an account
        self._queue.put((key, op, request, reply, t0, t1))

    def reloaded(self, key: str, label: str) -> None:
        if key in self._streams:
            now = time.time_ns()
            self._queue.put((key, None, label.encode(), b"", now, now))

    def answer(self, key: str, request: Any, restore: Callable[[], list[bytes]]) -> dict[str, Any]:
        """A recorder's ``P/admin/record`` request -> the host's answer. ``restore``: the
        requests that rebuild the key's live sessions, sent with a start so the recording
        begins with the state the planner had; asked once the stream is on, so a call the
        host takes meanwhile is in the stream (maybe in both), never in neither."""
        stream_id = request.get("stream") if isinstance(request, dict) else None
        if not isinstance(stream_id, str) or not stream_id.isalnum():
            return {
                "ok": False,
                "message": "a record request needs {action, stream (letters and digits), lease_s}",
            }
        action = request.get("action")
        lease = min(MAX_LEASE_S, max(0.5, float(request.get("lease_s") or 3.0)))
        with self._lock:
            found = [s for s in self._streams.get(key, []) if s.stream_id == stream_id]
            if action == "stop":
                for stream in found:
                    self._end(stream, "stopped by its recorder")
                return {"ok": True, "message": f"{key}: stream {stream_id} ended"}
            if action == "renew":
                for stream in found:
                    stream.expires = time.monotonic() + lease
                return {"ok": bool(found), "message": "renewed" if found else "no such stream"}
            if action != "start":
                return {"ok": False, "message": f"unknown record action {action!r}"}
            if not found:
                topic = KeySpace(key).record_stream(stream_id)
                publisher = self.session.declare_publisher(
                    topic,
                    reliability=zenoh.Reliability.RELIABLE,
                    # a slow recorder slows this thread, not the calls (the queue is bounded)
                    congestion_control=zenoh.CongestionControl.BLOCK,
                )
                stream = _Stream(key, stream_id, publisher, time.monotonic() + lease)
                self._streams.setdefault(key, []).append(stream)
                log.info("%s: streaming its calls to a live recorder on %s", key, topic)
        return {
            "ok": True,
            "message": f"{key}: streaming on {KeySpace(key).record_stream(stream_id)}",
            "metadata": self._metadata.get(key, {}),
            "restore": restore(),
            "lease_s": lease,
        }

    def _end(self, stream: _Stream, why: str) -> None:
        """With the lock held."""
        streams = self._streams.get(stream.key, [])
        if stream in streams:
            streams.remove(stream)
        if not streams:
            self._streams.pop(stream.key, None)
        with contextlib.suppress(Exception):
            stream.publisher.undeclare()
        log.info("%s: live recording stream %s ended: %s", stream.key, stream.stream_id, why)

    def _run(self) -> None:
        stopping = False
        while not stopping:
            try:
                first = self._queue.get(timeout=0.5)
            except queue.Empty:
                first = ()  # type: ignore[assignment]  # only leases to check
            if first is None:
                break
            if first:
                time.sleep(BATCH_S)  # one wake-up per batch, not per call
            batch, stopping = take_batch(self._queue, [first] if first else [])
            self._publish(batch)
            self._expire()

    def _publish(self, batch: list[Item]) -> None:
        with self._lock:
            for key, op, request, reply, t0, t1 in batch:
                self._queued_bytes -= len(request) + len(reply)
                for stream in self._streams.get(key, []):
                    try:
                        stream.publisher.put(msgpack.packb([op, request, reply, t0, t1]))
                    except Exception:
                        log.exception("%s: could not stream a call", key)

    def _expire(self) -> None:
        now = time.monotonic()
        with self._lock:
            for streams in list(self._streams.values()):
                for stream in list(streams):
                    if stream.expires < now:
                        self._end(stream, "its lease ran out (the recorder stopped renewing)")

    def close(self) -> None:
        if not self._thread.is_alive():
            return
        self._queue.put(None)
        self._thread.join(timeout=5.0)
        with self._lock:
            for streams in list(self._streams.values()):
                for stream in list(streams):
                    self._end(stream, "the host stops")
