"""Which planner hosts are alive on a key prefix, from their liveliness tokens."""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable
from typing import Any

import zenoh
from nav2_pyif_protocol.keys import KeySpace


class HostWatcher:
    """A liveliness subscriber with history (not a liveliness get: zenoh-pico's plugin side
    cannot use one across several tokens, and the reference client behaves as it does)."""

    def __init__(
        self,
        session: zenoh.Session,
        keys: KeySpace,
        on_change: Callable[[str, bool], None] | None = None,
    ) -> None:
        self._alive: set[str] = set()
        self._lock = threading.Lock()
        self._changed = threading.Condition(self._lock)
        self._on_change = on_change
        self._subscriber = session.liveliness().declare_subscriber(
            keys.hosts, self._on_sample, history=True
        )

    def _on_sample(self, sample: Any) -> None:
        host = KeySpace.host_id_of(str(sample.key_expr))
        alive = sample.kind == zenoh.SampleKind.PUT
        with self._changed:
            if alive:
                self._alive.add(host)
            else:
                self._alive.discard(host)
            self._changed.notify_all()
        if self._on_change is not None:
            self._on_change(host, alive)

    @property
    def alive(self) -> frozenset[str]:
        with self._lock:
            return frozenset(self._alive)

    def wait(self, timeout: float) -> bool:
        """Wait until at least one host is alive; False on timeout."""
        with self._changed:
            return self._changed.wait_for(lambda: bool(self._alive), timeout)

    def wait_for(self, predicate: Callable[[frozenset[str]], bool], timeout: float) -> bool:
        with self._changed:
            return self._changed.wait_for(lambda: predicate(frozenset(self._alive)), timeout)

    def close(self) -> None:
        with contextlib.suppress(Exception):  # the session may be closed already
            self._subscriber.undeclare()
