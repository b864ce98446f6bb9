"""Hot swap from outside: ask the host serving a key to load another planner (or a fresh
import of the same one) without dropping the key. What ``nav2-pyif reload`` sends."""

from __future__ import annotations

import time
from collections.abc import Callable

import msgpack
import zenoh
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.client.hosts import HostWatcher, visible_hosts
from nav2_pyif.exceptions import PlannerLoadError

#: How long to wait, by default, for a host's liveliness token to reach a fresh session.
DISCOVERY = 3.0


class NoPlannerHost(LookupError):
    """No planner host serves the key (none has declared its liveliness token there)."""


def wait_for_host(
    session: zenoh.Session,
    keys: KeySpace,
    wait: float = DISCOVERY,
    on_waiting: Callable[[str], None] | None = None,
) -> frozenset[str]:
    """The ids of the hosts serving ``keys`` once one's liveliness token is seen (a host
    declares it after its queryables: a query sent before would find nothing to answer it),
    waiting up to ``wait`` s; NoPlannerHost naming what is visible when none comes."""
    watcher = HostWatcher(session, keys)
    try:
        return _wait_for(watcher, session, keys, wait, on_waiting)
    finally:
        watcher.close()


def _wait_for(
    watcher: HostWatcher,
    session: zenoh.Session,
    keys: KeySpace,
    wait: float,
    on_waiting: Callable[[str], None] | None,
) -> frozenset[str]:
    looking = time.monotonic()
    if not watcher.wait(min(wait, DISCOVERY)) and wait > DISCOVERY:
        if on_waiting is not None:
            on_waiting(
                f"no planner host on {keys.prefix} yet, waiting up to {wait:g} s; "
                f"{visible_hosts(session)}"
            )
        watcher.wait(max(0.0, wait - (time.monotonic() - looking)))
    if not watcher.alive:
        raise NoPlannerHost(
            f"no planner host serves {keys.prefix} (no liveliness token under "
            f"{keys.hosts} after {time.monotonic() - looking:.1f} s); "
            f"{visible_hosts(session)}"
        )
    return watcher.alive


def request_reload(
    session: zenoh.Session,
    key_prefix: str,
    *,
    planner: str | None = None,
    module: str | None = None,
    delegates: dict[str, str] | None = None,
    allow_type_change: bool = False,
    timeout: float = 60.0,
    wait: float = DISCOVERY,
    on_waiting: Callable[[str], None] | None = None,
) -> str:
    """Returns the host's confirmation; raises PlannerLoadError with the host's reason when
    it refused (the old planner keeps serving), NoPlannerHost when no host serves the key
    (naming those that are visible), TimeoutError when a host did not answer in time.

    The reload is sent only once a host's liveliness token is seen on the key (the host
    declares it after its queryables: a query sent before would find nothing to answer it),
    waiting up to ``wait`` seconds for one; ``on_waiting`` is told, after DISCOVERY s without
    one, what this session sees meanwhile. ``timeout``: how long the host may take to load.
    ``allow_type_change``: let the new planner be of another plugin type than the key serves
    (the host refuses it otherwise, and always while a session is live)."""
    keys = KeySpace(key_prefix)
    watcher = HostWatcher(session, keys)
    try:
        _wait_for(watcher, session, keys, wait, on_waiting)
        started = time.monotonic()
        request = {
            "planner": planner,
            "module": module,
            "delegates": delegates,
            "allow_type_change": allow_type_change,
        }
        for reply in session.get(
            keys.admin_reload, payload=msgpack.packb(request), timeout=timeout
        ):
            if reply.ok is None:
                continue
            answer = msgpack.unpackb(reply.ok.payload.to_bytes())
            if not answer.get("ok"):
                raise PlannerLoadError(str(answer.get("message")))
            return str(answer.get("message"))
        waited, hosts = time.monotonic() - started, ", ".join(sorted(watcher.alive)) or "?"
    finally:
        watcher.close()
    if waited < 0.9 * timeout:
        raise NoPlannerHost(
            f"host {hosts} is alive on {key_prefix} but nothing answered a reload on "
            f"{keys.admin_reload} (after {waited:.1f} s; a router's access control that does "
            "not let this identity reload, a planner-host too old to reload, or it stopped "
            "meanwhile)"
        )
    raise TimeoutError(
        f"host {hosts} on {key_prefix} did not answer the reload within {timeout:g} s "
        "(still loading the new version? give it longer with --timeout)"
    )
