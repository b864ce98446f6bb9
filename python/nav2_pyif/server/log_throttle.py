"""A warning that any peer can cause as often as it likes (a refused remote reload) is logged
at most once a second; the next line says how many were held back meanwhile. A hostile peer
must not be able to fill the host's disk or drown its other messages."""

from __future__ import annotations

import logging
import threading
import time
from typing import Any


class ThrottledWarning:
    def __init__(self, logger: logging.Logger, every: float = 1.0) -> None:
        self.logger = logger
        self.every = every
        self.held = 0  # lines not logged since the last one that was
        self._next = 0.0
        self._lock = threading.Lock()

    def __call__(self, message: str, *args: Any) -> None:
        now = time.monotonic()
        with self._lock:
            if now < self._next:
                self.held += 1
                return
            held, self.held = self.held, 0
            self._next = now + self.every
        more = f" ({held} more like it since the last one logged)" if held else ""
        self.logger.warning(message + "%s", *args, more)
