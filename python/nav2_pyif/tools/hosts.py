"""``nav2-pyif hosts``: every live planner host this tool can see (the ``ros2 node list`` of
nav2_pyif), with the keys it serves, their planners, isolation, sessions and uptime.

Discovery as the plugin does it: a liveliness subscriber with history on ``**/host/*`` (the
token each host declares under every key prefix it serves), then a get on each prefix's
``admin/info`` (PROTOCOL.md section 1), answered by every host serving it."""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import dataclass, field
from typing import Any

import zenoh

from nav2_pyif.client.hosts import ALL_HOSTS, ask_info, collect_tokens
from nav2_pyif.common.option_types import positive_float
from nav2_pyif.common.reach import open_tool_session, unreachable
from nav2_pyif.common.zenoh_config import ZenohOptions, add_zenoh_arguments, options_from_args


@dataclass
class HostView:
    """One planner host: its tokens (key prefixes) and what each key's admin/info said."""

    host_id: str
    prefixes: set[str] = field(default_factory=set)
    info: dict[str, dict[str, Any]] = field(default_factory=dict)  # prefix -> admin/info

    def as_json(self, now: float) -> dict[str, Any]:
        first = next(iter(self.info.values()), {})
        started = first.get("started")
        return {
            "host_id": self.host_id,
            "hostname": first.get("hostname"),
            "pid": first.get("pid"),
            "started": started,
            "uptime": None if started is None else max(0.0, now - float(started)),
            "keys": [
                {
                    "key": prefix,
                    "planner": self.info.get(prefix, {}).get("planner"),
                    "plugin_type": self.info.get(prefix, {}).get("plugin_type"),
                    "isolation": self.info.get(prefix, {}).get("isolation"),
                    "sessions": self.info.get(prefix, {}).get("sessions"),
                    "queries": self.info.get(prefix, {}).get("queries"),
                    "answered": prefix in self.info,
                    # a batched controller's group: its keys, window, batches and cycles
                    "batch": self.info.get(prefix, {}).get("batch"),
                }
                for prefix in sorted(self.prefixes)
            ],
        }


@dataclass
class Survey:
    hosts: dict[str, HostView]
    routers: list[str]
    peers: list[str]

    def as_json(self) -> dict[str, Any]:
        now = time.time()
        return {
            "via": {"routers": self.routers, "peers": self.peers},
            "hosts": [self.hosts[h].as_json(now) for h in sorted(self.hosts)],
        }


def survey(session: zenoh.Session, wait: float = 1.0, timeout: float = 2.0) -> Survey:
    tokens = collect_tokens(session, wait)
    hosts = {h: HostView(h, prefixes) for h, prefixes in tokens.items()}
    prefixes = {p for view in hosts.values() for p in view.prefixes}
    for (prefix, host), info in ask_info(session, prefixes, timeout).items():
        if host in hosts and prefix in hosts[host].prefixes:
            hosts[host].info[prefix] = info
    return Survey(
        hosts,
        routers=[str(z) for z in session.info.routers_zid()],
        peers=[str(z) for z in session.info.peers_zid()],
    )


def via(found: Survey) -> str:
    parts = [f"router {z}" for z in found.routers] + [f"peer {z}" for z in found.peers]
    return ", ".join(parts)


def _uptime(seconds: float | None) -> str:
    if seconds is None:
        return "?"
    whole = int(seconds)
    if whole < 60:
        return f"{seconds:.1f} s"
    hours, rest = divmod(whole, 3600)
    return f"{hours}:{rest // 60:02d}:{rest % 60:02d}" if hours else f"{rest // 60}:{rest % 60:02d}"


def render(found: Survey) -> str:
    """The table, grouped by host."""
    header = ("KEY", "PLANNER", "TYPE", "ISOLATION", "SESSIONS", "QUERIES")
    lines = [f"via {via(found)}" if via(found) else "via nothing"]
    for item in found.as_json()["hosts"]:
        where = f"pid {item['pid']} on {item['hostname']}" if item["pid"] is not None else "?"
        lines += ["", f"host {item['host_id']}  ({where}, up {_uptime(item['uptime'])})"]
        rows = [header] + [
            (
                k["key"],
                k["planner"] or "? (no answer on admin/info: an older planner-host?)",
                k["plugin_type"] or "",
                k["isolation"] or "",
                "" if k["sessions"] is None else str(k["sessions"]),
                "" if k["queries"] is None else str(k["queries"]),
            )
            for k in item["keys"]
        ]
        widths = [max(len(r[i]) for r in rows) for i in range(len(header))]
        lines += [
            "  " + "  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip()
            for r in rows
        ]
        groups = {tuple(k["batch"]["keys"]): k["batch"] for k in item["keys"] if k["batch"]}
        lines += [
            f"  batched: {', '.join(keys)}: {group['cycles']} cycles in {group['batches']} "
            f"calls, window {group['window_s'] * 1e3:g} ms; not computed (overload): "
            f"{group.get('dropped', 0)} waited a period, {group.get('superseded', 0)} superseded"
            for keys, group in groups.items()
        ]
    return "\n".join(lines)


def nothing_found(found: Survey, options: ZenohOptions, wait: float) -> str:
    if not found.routers and not found.peers:
        return unreachable(options)
    return (
        f"reached {via(found)}, but no planner host is visible there (no liveliness token on "
        f"{ALL_HOSTS} within {wait:g} s)"
    )


def add_hosts_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "hosts",
        help="list the live planner hosts: keys, planners, sessions, queries, uptime",
        description="List every live planner host this tool can see through its Zenoh "
        "router or peers: the keys each serves, the planner, plugin type, isolation, "
        "number of live sessions and of queries answered per key (a call carried in another "
        "key's query is not one), its uptime, and the router or peer the tool went "
        "through. Exit code 0 when it found a host, 1 when none.",
    )
    p.add_argument(
        "--wait",
        type=positive_float,
        default=1.0,
        metavar="SECONDS",
        help="how long to collect the hosts' liveliness tokens, > 0 (default 1)",
    )
    p.add_argument(
        "--timeout",
        type=positive_float,
        default=2.0,
        metavar="SECONDS",
        help="how long the hosts may take to answer, > 0 (default 2)",
    )
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    add_zenoh_arguments(p, default_mode="client")
    p.set_defaults(func=run_hosts)


def run_hosts(args: argparse.Namespace) -> int:
    options = options_from_args(args)
    try:
        session = open_tool_session(options, "nav2-pyif hosts")
    except (FileNotFoundError, ConnectionError) as exc:  # a client reaching no router
        print(f"nav2-pyif hosts: {exc}", file=sys.stderr)
        return 1
    try:
        found = survey(session, args.wait, args.timeout)
    finally:
        session.close()
    if args.json:
        print(json.dumps(found.as_json(), indent=2))
    elif found.hosts:
        print(render(found))
    if not found.hosts:
        print(f"nav2-pyif hosts: {nothing_found(found, options, args.wait)}", file=sys.stderr)
        return 1
    return 0
