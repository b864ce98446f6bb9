"""What TLS costs: the control cycle (and a 1000-pose plan) through a Zenoh router on
loopback, over plain TCP, over TLS with client certificates (mutual TLS, as
python/doc/howto/deployment.md's secure fleet setup) and over mutual TLS with the router's access
control on, side by side in one run with interleaved rounds (so drift hits all alike).

    nav2-pyif-bench tls            # about a minute
    nav2-pyif-bench tls --quick    # a smoke run

Each variant: a router (``nav2-pyif router``), a planner host (a peer of that router, the
trivial controller in a worker process) and the reference client in client mode, as the C++
plugin is. Throwaway certificates are made in a temporary directory.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np
import zenoh
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif import Plan
from nav2_pyif.client import ControllerClient

from nav2_pyif_bench.pki import CertificateAuthority
from nav2_pyif_bench.processes import Peers, free_port, peer_processes
from nav2_pyif_bench.protocol_bench import (
    TIMEOUTS,
    costmap,
    interleaved,
    progress,
    timed,
)
from nav2_pyif_bench.stats import Summary, header_row

KEY = "nav2_pyif/bench/FollowPath"
VARIANTS = {
    "tcp": "plain TCP",
    "mtls": "TLS, client certificates (mTLS)",
    "mtls_acl": "mTLS + router access control",
}
ROBOT, HOST = "bench-robot", "planner-host"


def _tls(ca: CertificateAuthority, name: str, *, listen: bool = False) -> dict[str, Any]:
    identity = ca.issue(name, ("127.0.0.1", "localhost"))
    role = "listen" if listen else "connect"
    return {
        "root_ca_certificate": str(ca.certificate),
        f"{role}_certificate": str(identity.certificate),
        f"{role}_private_key": str(identity.private_key),
        "enable_mtls": True,
    }


def _access_control() -> dict[str, Any]:
    """The shape of docs/zenoh/router-secure.json5's rules, for one robot and its host."""

    def rule(rule_id: str, flow: str, messages: list[str]) -> dict[str, Any]:
        keys = ["nav2_pyif/bench/*/rpc/*", "nav2_pyif/bench/*/cancel", "nav2_pyif/bench/*/host/*"]
        return {"id": rule_id, "flows": [flow], "messages": messages, "key_exprs": keys,
                "permission": "allow"}  # fmt: skip

    return {
        "enabled": True,
        "default_permission": "deny",
        "rules": [
            rule("asks", "ingress", ["query", "declare_liveliness_subscriber"]),
            rule("hears", "egress", ["reply", "declare_queryable", "liveliness_token"]),
            rule("serves", "ingress", ["declare_queryable", "liveliness_token", "reply"]),
            rule("is-asked", "egress", ["query"]),
        ],
        "subjects": [
            {"id": "robot", "cert_common_names": [ROBOT]},
            {"id": "host", "cert_common_names": [HOST]},
        ],
        "policies": [
            {"rules": ["asks", "hears"], "subjects": ["robot"]},
            {"rules": ["serves", "is-asked"], "subjects": ["host"]},
        ],
    }


def write_configs(directory: Path) -> dict[str, dict[str, Path]]:
    """variant -> {router, host, client}: Zenoh JSON5 files in ``directory``."""
    ca = CertificateAuthority(directory / "certs")
    files: dict[str, dict[str, Path]] = {}
    for variant in VARIANTS:
        scheme = "tcp" if variant == "tcp" else "tls"
        endpoint = f"{scheme}/127.0.0.1:{free_port()}"
        base = {"scouting": {"multicast": {"enabled": False}}}
        link: dict[str, dict[str, Any]] = {"router": {}, "host": {}, "client": {}}
        if scheme == "tls":
            link = {
                "router": {"protocols": ["tls"], "tls": _tls(ca, "router", listen=True)},
                "host": {"protocols": ["tls"], "tls": _tls(ca, HOST)},
                "client": {"protocols": ["tls"], "tls": _tls(ca, ROBOT)},
            }
        configs = {
            "router": {"mode": "router", "listen": {"endpoints": [endpoint]}},
            "host": {
                "mode": "peer",
                "connect": {"endpoints": [endpoint]},
                "listen": {"endpoints": []},
            },
            "client": {"mode": "client", "connect": {"endpoints": [endpoint]}},
        }
        if variant == "mtls_acl":
            configs["router"]["access_control"] = _access_control()
        files[variant] = {}
        for role, config in configs.items():
            config.update(base, transport={"link": link[role], "shared_memory": {"enabled": False}})
            path = directory / f"{variant}-{role}.json5"
            path.write_text(json.dumps(config, indent=1))
            files[variant][role] = path
    return files


def _open_when_listening(config: Path, timeout: float = 30.0) -> zenoh.Session:
    """A client session: it fails to open until its router listens."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            return zenoh.open(zenoh.Config.from_file(str(config)))
        except Exception:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


def run(args: argparse.Namespace) -> dict[str, Any]:
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_tls_bench_") as tmp:
        files = write_configs(Path(tmp))
        commands: dict[str, list[str]] = {}
        for variant, paths in files.items():
            commands[f"{variant}-router"] = [
                *("-m", "nav2_pyif.tools.main", "router", "--zenoh-config", str(paths["router"]))
            ]
            commands[f"{variant}-host"] = [
                *("-m", "nav2_pyif.server.cli", "--zenoh-config", str(paths["host"]), "--key", KEY),
                *("--planner", "nav2_pyif_bench.planners:TrivialController"),
                *("--log-level", "WARNING"),
            ]
        with peer_processes(commands, {}) as peers:
            return _measure(files, args, peers)


def _measure(
    files: dict[str, dict[str, Path]], args: argparse.Namespace, peers: Peers
) -> dict[str, Any]:
    sessions: list[zenoh.Session] = []
    clients: dict[str, ControllerClient] = {}
    try:
        for variant, paths in files.items():
            progress(f"waiting for the {VARIANTS[variant]} router and host")
            sessions.append(_open_when_listening(paths["client"]))
            client = ControllerClient(sessions[-1], KEY, costmap(10), timeouts=TIMEOUTS)
            if not client.wait_for_host(30):
                raise peers.not_up(f"{variant}: the planner host")
            client.configure()
            client.activate()
            clients[variant] = client
        pose, velocity = PoseStamped(), Twist()
        pose.header.frame_id = "odom"

        def cycle(client: ControllerClient) -> Any:
            return lambda: timed(lambda: client.compute_velocity_commands(pose, velocity))

        cycles = interleaved(
            {v: cycle(c) for v, c in clients.items()}, args.rounds, args.calls, "control cycle"
        )
        plan = Plan(
            np.column_stack([np.arange(1000) * 0.05, np.zeros(1000), np.zeros(1000)]), "odom"
        )

        def send_plan(client: ControllerClient) -> Any:
            return lambda: timed(lambda: client.set_plan(plan))

        plans = interleaved(
            {v: send_plan(c) for v, c in clients.items()},
            max(1, args.rounds // 2),
            args.plan_calls,
            "1000-pose plan",
        )
        return {
            "cycle": {v: asdict(Summary.of_ns(s)) for v, s in cycles.items()},
            "plan_1000": {v: asdict(Summary.of_ns(s)) for v, s in plans.items()},
        }
    finally:
        for client in clients.values():
            client.close()
        for session in sessions:
            session.close()


def report(results: dict[str, Any]) -> str:
    lines: list[str] = []
    titles = {
        "cycle": "control cycle through a router on loopback (trivial planner, worker process)",
        "plan_1000": "1000-pose set_plan through the same router",
    }
    for section, title in titles.items():
        rows = {v: Summary(**d) for v, d in results[section].items()}
        tcp = rows["tcp"]
        lines += [title, header_row() + "   vs TCP (median, p99)"]
        for variant, summary in rows.items():
            ratios = f"{summary.median_us / tcp.median_us:.2f}, {summary.p99_us / tcp.p99_us:.2f}"
            lines.append(f"{summary.row(VARIANTS[variant])}   {ratios}")
        lines.append("")
    return "\n".join(lines).rstrip()
