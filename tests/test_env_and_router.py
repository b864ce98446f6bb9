"""Containers configure planner-host through NAV2_PYIF_* variables, and `nav2-pyif router`
routes between a host and a plugin that both only connect to it (the compose topology)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from geometry_msgs.msg import Twist
from nav2_pyif.client import ControllerClient
from nav2_pyif.common.env_defaults import apply_environment
from nav2_pyif.server.cli import build_parser

from tests.conftest import FIXTURES, free_port, make_costmap, wait_until
from tests.test_host_e2e import GENEROUS, pose

pytestmark = pytest.mark.integration


def parse(environ: dict[str, str], *argv: str) -> Any:
    parser = build_parser()
    apply_environment(parser, environ)
    return parser.parse_args(list(argv))


def test_variables_fill_options_and_flags_win() -> None:
    env = {
        "NAV2_PYIF_KEY": "robot1/FollowPath",
        "NAV2_PYIF_PLANNER": "a.b:C",
        "NAV2_PYIF_DEADLINE": "0.25",
        "NAV2_PYIF_CONNECT": "tcp/router:7447, tcp/backup:7447",
        "NAV2_PYIF_PATH": os.pathsep.join(["/planners", "/more"]),
        "NAV2_PYIF_MULTICAST_SCOUTING": "yes",
        "NAV2_PYIF_DELEGATE": "set_plan=sp,compute_velocity_commands=cv",
    }
    args = parse(env)
    assert (args.key, args.planner, args.deadline) == ("robot1/FollowPath", "a.b:C", 0.25)
    assert args.connect == ["tcp/router:7447", "tcp/backup:7447"]
    assert args.path == ["/planners", "/more"]
    assert args.multicast_scouting is True
    assert args.delegate == ["set_plan=sp,compute_velocity_commands=cv"]
    args = parse(env, "--deadline", "2", "--planner", "x.y:Z", "--connect", "tcp/other:1")
    assert (args.deadline, args.planner) == (2.0, "x.y:Z")
    assert args.connect == ["tcp/router:7447", "tcp/backup:7447", "tcp/other:1"]  # appended
    assert parse({}).deadline == 1.0 and parse({}).connect == []


def test_empty_variables_count_as_unset() -> None:
    """compose's ``NAV2_PYIF_CONFIG: ${CONFIG:-}`` leaves an empty value: not a file named ""
    (Path("") is "."), not an invalid deadline or log level."""
    names = ["CONFIG", "DEADLINE", "LOG_LEVEL", "KEY", "CONNECT", "MULTICAST_SCOUTING"]
    parser = build_parser()
    used = apply_environment(parser, {f"NAV2_PYIF_{name}": " " for name in names})
    args = parser.parse_args([])
    assert used == {}
    assert (args.config, args.deadline, args.log_level, args.key) == (None, 1.0, "INFO", None)
    assert (args.connect, args.multicast_scouting) == ([], False)


@pytest.mark.parametrize(
    ("variable", "value", "words"),
    [
        ("NAV2_PYIF_DEADLINE", "soon", "NAV2_PYIF_DEADLINE='soon'"),
        ("NAV2_PYIF_ISOLATION", "docker", "choose from process, none"),
        ("NAV2_PYIF_MULTICAST_SCOUTING", "maybe", "expected 1/true/yes/on"),
    ],
)
def test_a_bad_variable_is_a_usage_error_naming_it(variable: str, value: str, words: str) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.server.cli"],
        capture_output=True,
        text=True,
        timeout=30,
        env=dict(os.environ, **{variable: value}),
    )
    assert result.returncode == 2 and words in result.stderr, result.stderr


def test_help_names_the_variables() -> None:
    text = " ".join(build_parser().format_help().split())  # undo the wrapping
    assert "[env NAV2_PYIF_KEY]" in text and "[env NAV2_PYIF_PLAN_DEADLINE]" in text


def test_help_works_whatever_the_environment_holds() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.server.cli", "--help"],
        capture_output=True,
        text=True,
        timeout=30,
        env=dict(os.environ, NAV2_PYIF_DEADLINE="soon"),
    )
    assert result.returncode == 0 and "NAV2_PYIF_DEADLINE" in result.stdout


def start_router(
    *where: str, log: Path | None = None, env: dict[str, str] | None = None
) -> subprocess.Popen[str]:
    """``nav2-pyif router`` (``where``: --listen or --zenoh-config), once it listens; its
    output (Zenoh's log after the first line) in ``log`` if given."""
    command = [sys.executable, "-m", "nav2_pyif.tools.main", "router", *where]
    environ = {**os.environ, **(env or {})}
    if log is None:
        router = subprocess.Popen(command, stdout=subprocess.PIPE, text=True, env=environ)
        assert router.stdout is not None and "listening on" in router.stdout.readline()
        return router
    with open(log, "w") as out:
        router = subprocess.Popen(
            command, stdout=out, stderr=subprocess.STDOUT, text=True, env=environ
        )
    assert wait_until(lambda: "listening on" in log.read_text() or router.poll() is not None, 30)
    assert router.poll() is None, log.read_text()
    return router


@pytest.mark.parametrize("listen_from", ["flag", "config_file"])
def test_router_routes_between_a_host_and_a_client(
    tmp_path: Path, listen_from: str, zsession_factory: Any
) -> None:
    port = free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    if listen_from == "flag":
        where = ["--listen", endpoint]
    else:  # the file's endpoint, not the router's default tcp/0.0.0.0:7447
        config = tmp_path / "router.json5"
        config.write_text(f'{{mode: "router", listen: {{endpoints: ["{endpoint}"]}}}}')
        where = ["--zenoh-config", str(config)]
    router = start_router(*where)
    host_log = open(tmp_path / "host.log", "wb")  # noqa: SIM115 - closed below
    # The host is configured only through the environment, as in the container.
    host = subprocess.Popen(
        [sys.executable, "-m", "nav2_pyif.server.cli"],
        stdout=host_log,
        stderr=subprocess.STDOUT,
        env=dict(
            os.environ,
            NAV2_PYIF_CONNECT=f"tcp/127.0.0.1:{port}",
            NAV2_PYIF_KEY="nav2_pyif/routed/FollowPath",
            NAV2_PYIF_PLANNER="echo_planners:EchoController",
            NAV2_PYIF_PATH=str(FIXTURES),
            NAV2_PYIF_ISOLATION="none",
        ),
    )
    try:
        # Client mode, as the C++ plugin always is: the router forwards to the peer host.
        session = zsession_factory(endpoint, mode="client")
        client = ControllerClient(
            session, "nav2_pyif/routed/FollowPath", make_costmap(), timeouts=GENEROUS
        )
        assert client.wait_for_host(20), (tmp_path / "host.log").read_text()
        assert client.configure() == {"gain": 1.5, "label": "echo"}
        client.activate()
        assert client.compute_velocity_commands(pose(), Twist()).twist.linear.x == -1.0  # no plan
    finally:
        for proc in (host, router):
            proc.terminate()
        codes = [proc.wait(10) for proc in (host, router)]  # both stopped before asserting
        host_log.close()
        assert codes == [143, 143], (tmp_path / "host.log").read_text()  # SIGTERM


def test_a_host_that_reaches_nothing_keeps_saying_so_until_it_reaches_a_router(
    start_host: Any,
) -> None:
    router_at = f"tcp/127.0.0.1:{free_port()}"  # nothing there yet
    key, planner = "nav2_pyif/lonely/FollowPath", "echo_planners:EchoController"
    host = start_host("--key", key, "--planner", planner, "--connect", router_at)
    warning = "[WARNING] [nav2_pyif.server.host] Zenoh: nothing reached yet; "
    assert wait_until(
        lambda: (
            (
                f"{warning}no Zenoh router or peer answers at {router_at} and none connected "
                f"(listening on {host.endpoint}), so no Nav2 plugin can reach this host. Start "
                "a router there (zenohd, or nav2-pyif router)"
            )
            in host.log()
        ),
        20,
    ), host.log()
    assert wait_until(lambda: host.log().count(warning) >= 2, 15), host.log()  # repeated
    router = start_router("--listen", router_at)
    try:
        reached = "[INFO] [nav2_pyif.server.host] Zenoh: reached router "
        assert wait_until(lambda: reached in host.log(), 20), host.log()
    finally:
        router.terminate()
        router.wait(10)
    assert host.log().count("Zenoh: reached") == 1  # said once
