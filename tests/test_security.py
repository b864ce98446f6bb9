"""Closed to strangers: the deployment guide's secure fleet setup (section 6), run with its
exact files (docs/zenoh/*-secure.json5, *-password.json5; only the directory they name,
/etc/nav2_pyif/, and the endpoints are substituted). The router and its access control on
this machine, the planner host on a remote machine (its own network namespace behind a veth
link), strangers on that remote machine too. Certificates are made here, per test
(nav2_pyif_bench.pki).

Refused, each visibly in the router's log, with nothing served: a plain TCP peer, a TLS peer
without a client certificate, one whose certificate another CA signed, robot2 calling
robot1's key, robot1 asking for a reload. The authorised path works: robot1's plugin
(the reference client) configures, gets its plan and runs control cycles; an operator lists
the hosts and hot-swaps, within the host's reload allow-list only.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import msgpack
import numpy as np
import pytest
import zenoh
from geometry_msgs.msg import Twist
from nav2_pyif import Plan
from nav2_pyif.client import ControllerClient
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.recording.format import read_recording
from nav2_pyif.server.reload_policy import ReloadPolicy
from nav2_pyif.server.spec import PlannerSpec
from nav2_pyif.tools.admin import NoPlannerHost, request_reload
from nav2_pyif_bench.pki import CertificateAuthority

from tests.conftest import free_port, make_costmap, wait_until
from tests.docs_blocks import guide_certificates
from tests.netns import SUBNET, Link, namespace_link
from tests.test_env_and_router import start_router
from tests.test_host_e2e import GENEROUS, pose
from tests.test_network import start_remote_host, stop

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]
DOCS_ZENOH = ROOT / "docs" / "zenoh"
PLACEHOLDER = "/etc/nav2_pyif/"  # the guide's files name tls/*.pem and passwords.txt in it
#: passwords.txt as the password variant's files expect
PASSWORDS = {"robot1": "robot1-password-here", "planner-host": "host-password-here"}
KEY = "nav2_pyif/robot1/FollowPath"
#: Zenoh's warnings (refused TLS links), refused handshakes (wrong passwords) and access
#: control's decisions (denied messages): what python/doc/howto/deployment.md section 6 tells to log
ROUTER_LOG = {
    "RUST_LOG": "zenoh=warn,zenoh_transport::unicast::establishment::accept=debug,"
    "zenoh::net::routing::interceptor::access_control=trace"
}

#: A stranger on the remote machine: open a client session with CONFIG to ENDPOINT and, if
#: that works, ask KEY's configure. Prints what happened.
PROBE = """
import json, sys, zenoh
config = zenoh.Config.from_file(sys.argv[1])
config.insert_json5("connect/endpoints", json.dumps([sys.argv[2]]))
try:
    session = zenoh.open(config)
except Exception as exc:
    print("refused:", exc)
    sys.exit(0)
replies = [r for r in session.get(sys.argv[3] + "/rpc/configure", timeout=3.0) if r.ok]
print(f"opened: {len(replies)} replies")
session.close()
"""


def guide_config(name: str, root: Path, into: Path) -> Path:
    """docs/zenoh/NAME as written, with ``root`` for /etc/nav2_pyif."""
    path = into / f"{root.name}-{name}"
    path.write_text((DOCS_ZENOH / name).read_text().replace(PLACEHOLDER, f"{root}/"))
    return path


def without(config: Path, *words: str) -> Path:
    """A copy of ``config`` without the lines naming any of ``words``: a stranger's file."""
    lines = config.read_text().splitlines(True)
    copy = config.with_name(f"without-{'-'.join(words)}-{config.name}")
    copy.write_text("".join(line for line in lines if not any(w in line for w in words)))
    return copy


def open_with(config: Path, endpoint: str) -> zenoh.Session:
    """A session from a guide's file, connecting to ``endpoint`` instead of its example."""
    loaded = zenoh.Config.from_file(str(config))
    loaded.insert_json5("connect/endpoints", json.dumps([endpoint]))
    return zenoh.open(loaded)


def make_certificates(tmp_path: Path, router_address: str, maker: str) -> tuple[Path, Path]:
    """The fleet's certificates, made by the guide's openssl commands (``maker`` "openssl")
    or in Python with the same names, and a stranger's: the fleet's CA certificate (public)
    with robot1's name signed by another CA."""
    (tmp_path / "fleet").mkdir()
    if maker == "openssl":
        guide_certificates(tmp_path / "fleet", router_address)
    else:
        fleet = CertificateAuthority(tmp_path / "fleet" / "tls")
        fleet.issue("router", (router_address, "127.0.0.1", "localhost"))
        for name in ("robot1", "robot2", "planner-host", "operator"):
            fleet.issue(name)
    (tmp_path / "fleet" / "passwords.txt").write_text(
        "".join(f"{user}:{password}\n" for user, password in PASSWORDS.items())
    )
    stranger = tmp_path / "stranger"
    CertificateAuthority(stranger / "tls", "other-ca").issue("robot1")
    shutil.copy(tmp_path / "fleet" / "tls" / "ca.pem", stranger / "tls" / "ca.pem")
    return tmp_path / "fleet", stranger


@dataclass
class Fleet:
    link: Link
    endpoint: str  # the router's, reached from this machine and from the remote one
    certs: Path
    stranger_certs: Path
    tmp: Path
    router_log: Path
    host_log: Path

    def config(self, name: str, certs: Path | None = None) -> Path:
        return guide_config(name, certs or self.certs, self.tmp)

    def session(self, name: str) -> zenoh.Session:
        return open_with(self.config(name), self.endpoint)

    def probe(self, config: Path, endpoint: str | None = None) -> str:
        """A stranger's attempt from the remote machine."""
        result = subprocess.run(
            [
                *("ip", "netns", "exec", self.link.ns, sys.executable, "-c", PROBE),
                *(str(config), endpoint or self.endpoint, KEY),
            ],
            capture_output=True,
            text=True,
            timeout=60,
        )
        return result.stdout + result.stderr

    def router_says(self, pattern: str) -> bool:
        return wait_until(lambda: re.search(pattern, self.router_log.read_text()), 10)

    def tool(self, *args: str) -> subprocess.CompletedProcess[str]:
        """``nav2-pyif ARGS`` as the operator, with operator-secure.json5."""
        config = str(self.config("operator-secure.json5"))
        return subprocess.run(
            [
                *(sys.executable, "-m", "nav2_pyif.tools.main", *args),
                *("--zenoh-config", config, "--connect", self.endpoint),
            ],
            capture_output=True,
            text=True,
            timeout=90,
        )


@pytest.fixture
def fleet(tmp_path: Path, request: pytest.FixtureRequest) -> Iterator[Fleet]:
    """Router and remote host configured with the guide's files of one variant: "secure"
    (mutual TLS, the default) or "password"; "+openssl": the guide's openssl commands make
    the certificates."""
    variant, _, maker = getattr(request, "param", "secure").partition("+")
    with namespace_link() as link:
        endpoint = f"tls/{SUBNET}.1:{free_port()}"
        certs, stranger_certs = make_certificates(tmp_path, f"{SUBNET}.1", maker)
        fleet = Fleet(
            link,
            endpoint,
            certs,
            stranger_certs,
            tmp_path,
            tmp_path / "router.log",
            tmp_path / "host.log",
        )
        router = start_router(
            *("--zenoh-config", str(fleet.config(f"router-{variant}.json5")), "--listen", endpoint),
            log=fleet.router_log,
            env=ROUTER_LOG,
        )
        host = start_remote_host(
            link,
            fleet.host_log,
            *("--zenoh-config", str(fleet.config(f"host-{variant}.json5")), "--connect", endpoint),
            *("--key", KEY, "--planner", "echo_planners:EchoController", "--isolation", "none"),
            *("--allow-remote-reload", "--reload-allow", "echo_planners:Echo*"),
            "--allow-live-record",
        )
        try:
            assert wait_until(lambda: "ready" in fleet.host_log.read_text(), 30)
            yield fleet
        finally:
            stop([host, router])


def sessions_served(fleet: Fleet) -> int:
    """The host's live sessions on KEY, as ``nav2-pyif hosts`` shows them to the operator."""
    result = fleet.tool("hosts", "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    keys = [k for h in json.loads(result.stdout)["hosts"] for k in h["keys"]]
    return sum(int(k["sessions"]) for k in keys if k["key"] == KEY)


@pytest.mark.parametrize("fleet", ["secure", "secure+openssl"], indirect=True)
def test_strangers_are_refused_and_robot1_is_served(fleet: Fleet) -> None:
    plain = guide_config("plugin-client.json5", fleet.certs, fleet.tmp)
    assert "refused" in fleet.probe(plain, fleet.endpoint.replace("tls/", "tcp/"))
    assert fleet.router_says("corrupt message")  # plain TCP on the TLS port
    no_certificate = without(fleet.config("plugin-secure.json5"), "connect_", "enable_mtls")
    assert "refused" in fleet.probe(no_certificate)
    assert fleet.router_says("peer sent no certificates")
    wrong_ca = fleet.config("plugin-secure.json5", fleet.stranger_certs)
    assert "refused" in fleet.probe(wrong_ca)
    assert fleet.router_says("invalid peer certificate: UnknownIssuer")

    # robot2 (robot2's plugin file: the same with robot2's certificate) calling robot1's key
    robot2_config = fleet.config("plugin-secure.json5").read_text().replace("robot1", "robot2")
    (fleet.tmp / "robot2.json5").write_text(robot2_config)
    robot2 = open_with(fleet.tmp / "robot2.json5", fleet.endpoint)
    try:
        assert [r for r in robot2.get(f"{KEY}/rpc/configure", timeout=2.0) if r.ok] == []
        client = ControllerClient(robot2, KEY, make_costmap(), timeouts=GENEROUS)
        assert not client.wait_for_host(2)  # robot1's host is invisible to robot2
        client.close()
    finally:
        robot2.close()
    assert fleet.router_says(
        r"CertCommonName\(robot2\).*unauthorized to Query \(ingress\) on " + f"{KEY}/rpc/configure"
    )
    assert sessions_served(fleet) == 0  # nothing reached the host

    robot1 = fleet.session("plugin-secure.json5")
    client = ControllerClient(robot1, KEY, make_costmap(), timeouts=GENEROUS)
    try:
        assert client.wait_for_host(20), fleet.host_log.read_text()
        assert client.configure() == {"gain": 1.5, "label": "echo"}
        client.activate()
        client.set_plan(Plan(np.zeros((17, 3)), "odom"))
        for _ in range(3):
            assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == 17
        assert sessions_served(fleet) == 1
        # the benchmark against a running host, as robot1 (its certificate and file)
        timed = subprocess.run(
            [
                *(sys.executable, "-m", "nav2_pyif_bench.cli", "host", "--key", KEY),
                *("--zenoh-config", str(fleet.config("plugin-secure.json5"))),
                *("--connect", fleet.endpoint, "--calls", "20", "--rate", "0"),
            ],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert timed.returncode == 0, timed.stderr
        assert "compute_velocity_commands round trip" in timed.stdout, timed.stdout

        # robot1 may call its planner, not swap it: the router drops the query
        with pytest.raises(NoPlannerHost, match="access control"):
            request_reload(robot1, KEY, planner="echo_planners:EchoController", timeout=5)
        assert fleet.router_says(
            r"CertCommonName\(robot1\).*unauthorized to Query \(ingress\) on "
            + f"{KEY}/admin/reload"
        )
        assert "reload" not in fleet.host_log.read_text()  # never reached the host

        # the operator may, within the host's allow-list (echo_planners:Echo*)
        swapped = fleet.tool("reload", "--key", KEY, "--planner", "echo_planners:EchoController")
        assert "now serving echo_planners:EchoController" in swapped.stdout, swapped.stderr
        refused = fleet.tool("reload", "--key", KEY, "--planner", "echo_planners:LinePlanner")
        assert refused.returncode == 1
        assert "not in this host's reload allow-list" in refused.stderr
        assert "refused a remote reload (echo_planners:LinePlanner)" in fleet.host_log.read_text()

        # the operator may record robot1's calls live, to a file on its own machine
        out, said = fleet.tmp / "operator.mcap", []
        record = ("record", "--key", KEY, "-o", str(out), "--duration", "5")
        recording = threading.Thread(target=lambda: said.append(fleet.tool(*record)))
        recording.start()
        assert wait_until(lambda: "live recorder" in fleet.host_log.read_text(), 30)
        for _ in range(5):
            client.compute_velocity_commands(pose(), Twist())
        recording.join(timeout=60)
        assert said and said[0].returncode == 0, said and said[0].stderr
        ops = [c.op for c in read_recording([out]).calls]
        assert ops.count("compute_velocity_commands") == 5, ops
        assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == 17
    finally:
        client.close()
        robot1.close()


@pytest.mark.parametrize("fleet", ["password"], indirect=True)
def test_passwords_the_lighter_option(fleet: Fleet) -> None:
    """User names and passwords (TLS without client certificates): a wrong password or none
    is refused; robot1 with its password is served, and may not reload."""
    written = fleet.config("plugin-password.json5").read_text()
    wrong = fleet.tmp / "wrong-password.json5"
    wrong.write_text(written.replace(PASSWORDS["robot1"], "guessed"))
    assert "refused" in fleet.probe(wrong)
    assert fleet.router_says("UsrPwd extension - Recv OpenSyn. Invalid password")
    assert "refused" in fleet.probe(without(fleet.config("plugin-password.json5"), "usrpwd"))
    assert fleet.router_says("UsrPwd extension - Recv InitSyn. Expected extension")

    robot1 = fleet.session("plugin-password.json5")
    client = ControllerClient(robot1, KEY, make_costmap(), timeouts=GENEROUS)
    try:
        assert client.wait_for_host(20), fleet.host_log.read_text()
        client.configure()
        client.activate()
        client.set_plan(Plan(np.zeros((17, 3)), "odom"))
        assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == 17
        with pytest.raises(NoPlannerHost, match="access control"):
            request_reload(robot1, KEY, timeout=5)
        assert fleet.router_says(
            r"Username\(robot1\).*unauthorized to Query \(ingress\) on " + f"{KEY}/admin/reload"
        )
        # nor record its calls, though its host allows live recording: the router decides who
        start = msgpack.packb({"action": "start", "stream": "robot1", "lease_s": 3.0})
        assert [
            r for r in robot1.get(f"{KEY}/admin/record", payload=start, timeout=3) if r.ok
        ] == []
        assert fleet.router_says(
            r"Username\(robot1\).*unauthorized to Query \(ingress\) on " + f"{KEY}/admin/record"
        )
        assert "live recorder" not in fleet.host_log.read_text()  # never reached the host
    finally:
        client.close()
        robot1.close()


@pytest.mark.parametrize(
    ("policy", "requested", "refused"),
    [
        (ReloadPolicy(), None, "remote reloads are off on this host"),
        (ReloadPolicy(True), None, None),  # a fresh import of what the key serves
        (ReloadPolicy(True), PlannerSpec(KEY, "other:Other"), "not in this host's reload"),
        (ReloadPolicy(True, ("my_planners.*",)), PlannerSpec(KEY, "my_planners.a:A"), None),
        (ReloadPolicy(True, ("my_planners.a",)), PlannerSpec(KEY, "my_planners.a:A"), None),
        (ReloadPolicy(True, ("my_planners.a:B*",)), PlannerSpec(KEY, "my_planners.a:A"), "not in"),
        (ReloadPolicy(True, ("seed_*",)), PlannerSpec(KEY, module="seed_apf"), None),
        (ReloadPolicy(True, ("my_planners.*",)), PlannerSpec(KEY, "os:system"), "not in"),
    ],
)
def test_reload_policy(
    policy: ReloadPolicy, requested: PlannerSpec | None, refused: str | None
) -> None:
    reason = policy.refusal(requested)
    assert (reason is None) == (refused is None) and (refused or "") in (reason or "")


def test_a_host_refuses_remote_reloads_by_default(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", KEY, "--planner", "echo_planners:EchoController")
    session = zsession_factory(host.endpoint)
    client = ControllerClient(session, KEY, make_costmap(), timeouts=GENEROUS)
    assert client.wait_for_host(30), host.log()
    with pytest.raises(
        PlannerLoadError, match="reload refused by the host: remote reloads are off"
    ):
        request_reload(session, KEY, timeout=30)
    assert (
        "refused a remote reload (a fresh import of echo_planners:EchoController): remote"
        in host.log()
    )
    client.close()


def test_reload_allow_needs_allow_remote_reload() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.server.cli", "--reload-allow", "x.*", "--key", "a/b"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert result.returncode == 2 and "--reload-allow needs --allow-remote-reload" in result.stderr
