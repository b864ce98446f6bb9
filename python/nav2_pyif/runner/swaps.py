"""Hot swaps during a run (``nav2-pyif reload``, SIGHUP of the host): which planner served each
role when, from the history each host keeps per key (its ``admin/info``), asked once at the
end of the run: nothing is asked while the robot drives."""

from __future__ import annotations

import bisect
from dataclasses import dataclass
from typing import Any

import zenoh

from nav2_pyif.client.hosts import ask_info
from nav2_pyif.client.plugin_client import PluginClient


@dataclass(frozen=True)
class Swap:
    sim_time: float  # [s] simulated time of the first cycle the new planner served
    role: str  # "controller", "planner", ... (the runner's roles)
    planner: str  # the host's label of the planner swapped in


def swaps_during(
    session: zenoh.Session,
    clients: dict[str, PluginClient],
    since: float,
    clock: list[float],
    sim_times: list[float],
    timeout: float = 2.0,
) -> list[Swap]:
    """The swaps of each role's key after unix time ``since``, on the host the client used;
    ``clock``: the unix time of each cycle, ``sim_times`` its simulated time."""
    by_prefix = {client.keys.prefix: (role, client) for role, client in clients.items()}
    swaps = []
    for (prefix, host_id), info in ask_info(session, set(by_prefix), timeout).items():
        role, client = by_prefix[prefix]
        if client.host is not None and host_id != client.host:
            continue  # a replica this run did not use
        for when, label in _history(info):
            if when > since:
                swaps.append(Swap(_sim_time(when, clock, sim_times), role, label))
    return sorted(swaps, key=lambda s: s.sim_time)


def _history(info: dict[str, Any]) -> list[tuple[float, str]]:
    """(unix time, label) pairs; none from a host older than the history field."""
    entries = info.get("history") or []
    return [
        (float(e[0]), str(e[1])) for e in entries if isinstance(e, list | tuple) and len(e) == 2
    ]


def _sim_time(when: float, clock: list[float], sim_times: list[float]) -> float:
    """The simulated time of the first cycle at or after unix time ``when``."""
    i = bisect.bisect_left(clock, when)
    if i >= len(sim_times):
        return sim_times[-1] if sim_times else 0.0
    return sim_times[i - 1] if i else 0.0  # the cycle's row is stamped at its end
