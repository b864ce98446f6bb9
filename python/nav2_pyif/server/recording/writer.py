"""The MCAP files of one recording: channels made on first use, size-bounded, rotated.

Runs on the recorder's thread only (not thread-safe). The first file is the path asked for;
when one passes ``max_bytes`` the next is ``<stem>.1.mcap``, ``<stem>.2.mcap``, ..., and only the
newest ``max_files`` are kept, so a recording never takes more than about
``max_bytes * max_files`` of disk. A host started again on the same path goes on numbering.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from nav2_pyif.server.recording.format import ENCODING, LIBRARY, PROFILE, RELOAD, RESTORE

log = logging.getLogger("nav2_pyif.recording")


def rotated_path(first: Path, index: int) -> Path:
    return first if index == 0 else first.with_name(f"{first.stem}.{index}{first.suffix}")


def index_of(first: Path, path: Path) -> int:
    """``path``'s place among ``first``'s rotated files (-1: not one of them)."""
    if path == first:
        return 0
    middle = path.name.removeprefix(first.stem + ".").removesuffix(first.suffix)
    return int(middle) if middle.isdigit() and path.name != middle else -1


def existing_files(first: Path) -> list[Path]:
    """The rotated files of ``first`` already on disk, oldest first."""
    found = [
        p for p in first.parent.glob(f"{first.stem}*{first.suffix}") if index_of(first, p) >= 0
    ]
    return sorted(found, key=lambda p: index_of(first, p))


class RotatingWriter:
    def __init__(
        self,
        path: Path,
        max_bytes: int,
        max_files: int,
        key_metadata: Callable[[str], dict[str, str]],
    ) -> None:
        self.first = path
        self.max_bytes, self.max_files = max_bytes, max_files
        self.key_metadata = key_metadata  # the key's plugin type and planner, for channels
        # A host started again on the same FILE (--respawn, a restart) goes on after the files
        # its last run left, which count towards max_files: nothing recorded is overwritten.
        self.paths: list[Path] = existing_files(path)  # the files kept, oldest first
        self.index = index_of(path, self.paths[-1]) if self.paths else -1
        self._stream: IO[bytes] | None = None
        self._writer: Any = None
        self._channels: dict[tuple[str, str], int] = {}
        self._schema = 0
        self.open_next()

    def open_next(self) -> None:
        from mcap.writer import Writer

        self.close()
        self.index += 1
        path = rotated_path(self.first, self.index)
        self._stream = open(path, "wb")  # noqa: SIM115 (closed in close())
        # chunks below the file bound, so the size seen on disk trails the writes by little
        self._writer = Writer(self._stream, chunk_size=max(4096, min(1 << 20, self.max_bytes // 8)))
        self._writer.start(profile=PROFILE, library=LIBRARY)
        self._channels.clear()
        self.paths.append(path)
        while len(self.paths) > self.max_files:
            oldest = self.paths.pop(0)
            oldest.unlink(missing_ok=True)
            log.info("recording: removed %s (more than %d files)", oldest, self.max_files)

    @property
    def full(self) -> bool:
        return self._stream is not None and self._stream.tell() >= self.max_bytes

    def channel(self, key: str, topic: str, kind: str, op: str = "") -> int:
        found = self._channels.get((topic, kind))
        if found is not None:
            return found
        metadata = {"key": key, "kind": kind, **self.key_metadata(key)}
        if op:
            metadata["op"] = op
        channel_id: int = self._writer.register_channel(topic, ENCODING, self._schema, metadata)
        self._channels[(topic, kind)] = channel_id
        return channel_id

    def write(self, channel_id: int, data: bytes, log_ns: int, publish_ns: int, seq: int) -> None:
        self._writer.add_message(channel_id, log_ns, data, publish_ns, seq)

    def note(self, key: str, kind: str, data: bytes, when_ns: int, seq: int = 0) -> None:
        """A restore request or a reload on the key's channel of that kind."""
        assert kind in (RESTORE, RELOAD)
        self.write(self.channel(key, f"{key}/{kind}", kind), data, when_ns, when_ns, seq)

    def metadata(self, name: str, values: dict[str, Any]) -> None:
        self._writer.add_metadata(name, {k: json.dumps(v) for k, v in values.items()})

    def close(self) -> None:
        if self._writer is not None:
            self._writer.finish()
            self._writer = None
        if self._stream is not None:
            self._stream.close()
            self._stream = None
