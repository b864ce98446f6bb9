"""What a plugin client needs of Zenoh, as an interface (the C++ plugin's
client/transport.hpp): a query with a timeout, a query nobody waits on, and the hosts alive on
a key prefix. ``ZenohTransport`` is the real one; ``MockTransport`` answers from a function, in
no time, so the client's rules are tested without Zenoh or real time (httpx's MockTransport).
"""

from __future__ import annotations

import threading
import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable
from typing import Any, Protocol

import zenoh
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.client.hosts import HostWatcher

#: How often a query with work to do while it waits (a cancel checker) polls for its reply.
POLL_S = 0.005


class Hosts(Protocol):
    """The planner hosts alive on one key prefix (HostWatcher's interface)."""

    @property
    def alive(self) -> frozenset[str]: ...

    def wait(self, timeout: float) -> bool: ...

    def wait_for(self, predicate: Callable[[frozenset[str]], bool], timeout: float) -> bool: ...

    def close(self) -> None: ...


class Transport(ABC):
    @abstractmethod
    def query(
        self,
        key: str,
        host: str | None,
        payload: bytes,
        timeout: float,
        poll: Callable[[], None] | None = None,
    ) -> bytes | None:
        """One query (target ALL) on ``key``, for the replica ``host`` (None: any): the
        payload of the first successful reply, or None when none came within ``timeout``
        seconds. ``poll`` runs about every POLL_S meanwhile."""

    @abstractmethod
    def send(self, key: str, host: str | None, payload: bytes, timeout: float) -> None:
        """A query whose replies nobody waits for (cancel_plan)."""

    @abstractmethod
    def hosts(self, keys: KeySpace) -> Hosts:
        """A watch of the host tokens under ``keys``' prefix."""


def selector(key: str, host: str | None) -> str:
    """``key?host=<id>``: replicas other than ``host`` drop the query (PROTOCOL.md section 1)."""
    return f"{key}?host={host}" if host else key


class ZenohTransport(Transport):
    def __init__(self, session: zenoh.Session) -> None:
        self.session = session

    def query(
        self,
        key: str,
        host: str | None,
        payload: bytes,
        timeout: float,
        poll: Callable[[], None] | None = None,
    ) -> bytes | None:
        replies = self.session.get(
            selector(key, host), payload=payload, timeout=timeout, target=zenoh.QueryTarget.ALL
        )
        sample = _first_ok(replies) if poll is None else _polling(replies, timeout, poll)
        return None if sample is None else bytes(sample.payload.to_bytes())

    def send(self, key: str, host: str | None, payload: bytes, timeout: float) -> None:
        self.session.get(
            selector(key, host), payload=payload, timeout=timeout, target=zenoh.QueryTarget.ALL
        )

    def hosts(self, keys: KeySpace) -> Hosts:
        return HostWatcher(self.session, keys)


def _first_ok(replies: Iterable[Any]) -> Any:
    """The first successful Zenoh reply, or None when the query ended without one."""
    for reply in replies:
        if reply.ok is not None:
            return reply.ok
    return None


def _polling(replies: Any, timeout: float, poll: Callable[[], None]) -> Any:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            reply = replies.try_recv()
        except Exception:  # the query ended (its own timeout) without a reply
            return None
        if reply is not None:
            if reply.ok is not None:
                return reply.ok
            continue  # an error (e.g. a timeout marker): keep waiting for the deadline
        poll()
        time.sleep(POLL_S)
    return None


class StaticHosts:
    """Hosts a test sets (``set``); waits return at once, with what is alive then."""

    def __init__(self, alive: Iterable[str] = ()) -> None:
        self._alive = frozenset(alive)
        self._lock = threading.Lock()

    def set(self, alive: Iterable[str]) -> None:
        with self._lock:
            self._alive = frozenset(alive)

    @property
    def alive(self) -> frozenset[str]:
        with self._lock:
            return self._alive

    def wait(self, timeout: float) -> bool:
        return bool(self.alive)

    def wait_for(self, predicate: Callable[[frozenset[str]], bool], timeout: float) -> bool:
        return predicate(self.alive)

    def close(self) -> None:
        pass


#: A mock host: (key, host, payload, timeout [s]) -> the reply's payload, or None for silence.
Handler = Callable[[str, str | None, bytes, float], bytes | None]


class MockTransport(Transport):
    """Every query answered by ``handler`` at once (silence costs no time); one StaticHosts
    for every key prefix."""

    def __init__(self, handler: Handler, hosts: StaticHosts | None = None) -> None:
        self.handler = handler
        self.static_hosts = hosts or StaticHosts()

    def query(
        self,
        key: str,
        host: str | None,
        payload: bytes,
        timeout: float,
        poll: Callable[[], None] | None = None,
    ) -> bytes | None:
        return self.handler(key, host, payload, timeout)

    def send(self, key: str, host: str | None, payload: bytes, timeout: float) -> None:
        self.handler(key, host, payload, timeout)

    def hosts(self, keys: KeySpace) -> Hosts:
        return self.static_hosts
