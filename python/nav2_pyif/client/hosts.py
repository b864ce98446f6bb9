"""Which planner hosts are alive on a key prefix (or on every prefix), from their liveliness
tokens; what each serves there, from its ``admin/info``."""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Callable
from typing import Any

import msgpack
import zenoh
from nav2_pyif_protocol.keys import KeySpace

#: Every planner host's token, whatever key prefix it serves.
ALL_HOSTS = "**/host/*"


class HostWatcher:
    """A liveliness subscriber with history (not a liveliness get: zenoh-pico's plugin side
    cannot use one across several tokens, and the reference client behaves as it does), on
    one key prefix's host tokens or on a key expression over several (``ALL_HOSTS``)."""

    def __init__(
        self,
        session: zenoh.Session,
        keys: KeySpace | str,
        on_change: Callable[[str, bool], None] | None = None,
    ) -> None:
        self._tokens: set[tuple[str, str]] = set()  # (key prefix, host id)
        self._lock = threading.Lock()
        self._changed = threading.Condition(self._lock)
        self._on_change = on_change
        self._subscriber = session.liveliness().declare_subscriber(
            keys.hosts if isinstance(keys, KeySpace) else keys, self._on_sample, history=True
        )

    def _on_sample(self, sample: Any) -> None:
        prefix, _, host = str(sample.key_expr).rpartition("/host/")
        alive = sample.kind == zenoh.SampleKind.PUT
        with self._changed:
            if alive:
                self._tokens.add((prefix, host))
            else:
                self._tokens.discard((prefix, host))
            self._changed.notify_all()
        if self._on_change is not None:
            self._on_change(host, alive)

    def _hosts(self) -> frozenset[str]:  # with the lock held
        return frozenset(host for _, host in self._tokens)

    @property
    def alive(self) -> frozenset[str]:
        with self._lock:
            return self._hosts()

    @property
    def tokens(self) -> frozenset[tuple[str, str]]:
        """Every live token as (key prefix, host id)."""
        with self._lock:
            return frozenset(self._tokens)

    def wait(self, timeout: float) -> bool:
        """Wait until at least one host is alive; False on timeout."""
        with self._changed:
            return self._changed.wait_for(lambda: bool(self._tokens), timeout)

    def wait_for(self, predicate: Callable[[frozenset[str]], bool], timeout: float) -> bool:
        with self._changed:
            return self._changed.wait_for(lambda: predicate(self._hosts()), timeout)

    def close(self) -> None:
        with contextlib.suppress(Exception):  # the session may be closed already
            self._subscriber.undeclare()


def collect_tokens(session: zenoh.Session, wait: float) -> dict[str, set[str]]:
    """host id -> key prefixes, from every host token alive after ``wait`` seconds."""
    watcher = HostWatcher(session, ALL_HOSTS)
    try:
        time.sleep(wait)
    finally:
        watcher.close()
    hosts: dict[str, set[str]] = {}
    for prefix, host in watcher.tokens:
        hosts.setdefault(host, set()).add(prefix)
    return hosts


def reached(session: zenoh.Session) -> str:
    """The routers and peers this session is connected to ("router 3bb4..., peer 30c8..."),
    or "" when it reaches nothing."""
    parts = [f"router {z}" for z in session.info.routers_zid()]
    return ", ".join(parts + [f"peer {z}" for z in session.info.peers_zid()])


def visible_hosts(session: zenoh.Session, wait: float = 1.0) -> str:
    """The planner hosts this session sees, by key prefix, and what it went through, as a
    sentence: what a tool that finds no host on its key tells the user."""
    served: dict[str, set[str]] = {}
    for host, prefixes in collect_tokens(session, wait).items():
        for prefix in prefixes:
            served.setdefault(prefix, set()).add(host)
    where = reached(session)
    if not served:
        if not where:
            return (
                "no planner host is visible at all from here: this session reaches no Zenoh "
                "router or peer (--connect / --zenoh-config)"
            )
        return (
            f"no planner host is visible at all from here (reached {where}, but no host token "
            f"under {ALL_HOSTS} within {wait:g} s)"
        )
    listed = "; ".join(f"{p} (host {', '.join(sorted(h))})" for p, h in sorted(served.items()))
    return f"planner hosts visible from here: {listed}; reached {where}"


def ask_info(
    session: zenoh.Session, prefixes: set[str], timeout: float
) -> dict[tuple[str, str], dict[str, Any]]:
    """(prefix, host id) -> admin/info reply, from every host answering on each prefix (all
    gets in flight at once)."""
    pending = [
        session.get(
            KeySpace(prefix).admin_info,
            target=zenoh.QueryTarget.ALL,
            consolidation=zenoh.ConsolidationMode.NONE,  # replicas answer on the same key
            timeout=timeout,
        )
        for prefix in sorted(prefixes)
    ]
    answers: dict[tuple[str, str], dict[str, Any]] = {}
    for replies in pending:
        for reply in replies:
            if reply.ok is None:
                continue
            try:
                info = msgpack.unpackb(reply.ok.payload.to_bytes())
                answers[(str(info["key"]), str(info["host_id"]))] = info
            except Exception:
                continue  # not a planner host's answer
    return answers
