"""Hot swap from outside: ask the host serving a key to load another planner (or a fresh
import of the same one) without dropping the key. What ``nav2-pyif reload`` sends."""

from __future__ import annotations

import time

import msgpack
import zenoh
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.client.hosts import HostWatcher, collect_tokens
from nav2_pyif.exceptions import PlannerLoadError

#: How long to wait for a host's liveliness token to reach a freshly opened session.
DISCOVERY = 3.0


class NoPlannerHost(LookupError):
    """No planner host serves the key (none has declared its liveliness token there)."""


def request_reload(
    session: zenoh.Session,
    key_prefix: str,
    *,
    planner: str | None = None,
    module: str | None = None,
    delegates: dict[str, str] | None = None,
    timeout: float = 60.0,
) -> str:
    """Returns the host's confirmation; raises PlannerLoadError with the host's reason when
    it refused (the old planner keeps serving), NoPlannerHost when no host serves the key
    (naming those that are visible), TimeoutError when a host did not answer in time."""
    keys = KeySpace(key_prefix)
    watcher = HostWatcher(session, keys)
    try:
        if not watcher.wait(min(timeout, DISCOVERY)):
            raise NoPlannerHost(
                f"no planner host serves {key_prefix} (no liveliness token under "
                f"{keys.hosts} after {min(timeout, DISCOVERY):g} s); {visible_hosts(session)}"
            )
        started = time.monotonic()
        request = {"planner": planner, "module": module, "delegates": delegates}
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


def visible_hosts(session: zenoh.Session, timeout: float = 1.0) -> str:
    """The planner hosts this session sees, by key prefix, as a sentence."""
    served: dict[str, set[str]] = {}
    for host, prefixes in collect_tokens(session, timeout).items():
        for prefix in prefixes:
            served.setdefault(prefix, set()).add(host)
    if not served:
        return (
            "no planner host is visible at all from here: is this tool on the hosts' Zenoh "
            "network (--connect / --zenoh-config)?"
        )
    listed = "; ".join(f"{p} (host {', '.join(sorted(h))})" for p, h in sorted(served.items()))
    return f"planner hosts visible from here: {listed}"
