"""Length-prefixed messages over one end of a pipe, for the supervisor <-> worker call path.

``multiprocessing.Connection`` costs two reads per message (its header, then the body) and a
few layers of Python per call; the control cycle crosses the pipe twice per call. Here a
message is a 4-byte big-endian length and the bytes, written with one ``os.write`` and
usually read with one ``os.read`` (what a read brings beyond the message is kept for the
next). Both ends of a call pipe must use this class.
"""

from __future__ import annotations

import os
import struct
from multiprocessing.connection import Connection

_HEADER = struct.Struct(">I")
_CHUNK = 1 << 16


class FramedPipe:
    """One end of a duplex ``multiprocessing.Pipe``, read and written as whole messages. When
    the other end is gone, recv raises EOFError and send BrokenPipeError (an OSError)."""

    def __init__(self, connection: Connection) -> None:
        self.connection = connection  # owns the file descriptor
        self._fd = connection.fileno()
        self._buffer = b""

    def fileno(self) -> int:
        return self._fd

    def send(self, message: bytes) -> None:
        data = memoryview(_HEADER.pack(len(message)) + message)
        while data:
            data = data[os.write(self._fd, data) :]

    def pending(self) -> bool:
        """True when a whole message already sits in the buffer (no read needed)."""
        return len(self._buffer) >= _HEADER.size and len(self._buffer) >= (
            _HEADER.size + _HEADER.unpack_from(self._buffer)[0]
        )

    def recv(self) -> bytes:
        buffer = self._buffer
        while len(buffer) < _HEADER.size:
            buffer += self._read()
        end = _HEADER.size + _HEADER.unpack_from(buffer)[0]
        if len(buffer) < end:  # a large message (a costmap, a plan): joined once
            parts, have = [buffer], len(buffer)
            while have < end:
                parts.append(self._read(end - have))
                have += len(parts[-1])
            buffer = b"".join(parts)
        self._buffer = buffer[end:]
        return buffer[_HEADER.size : end]

    def _read(self, wanted: int = _CHUNK) -> bytes:
        chunk = os.read(self._fd, max(wanted, _CHUNK))
        if not chunk:
            raise EOFError("the other end of the pipe is closed")
        return chunk

    def close(self) -> None:
        self.connection.close()
