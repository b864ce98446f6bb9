"""Bad input to every command is a usage error (exit 2) before anything starts: it names the
option or variable and the form or range expected, never a traceback.
Each case runs the real command."""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import zenoh
from nav2_pyif.common.option_types import endpoint

from tests.conftest import FIXTURES, free_port

pytestmark = pytest.mark.integration

COMMANDS = {
    "planner-host": ["-m", "nav2_pyif.server.cli"],
    "nav2-pyif": ["-m", "nav2_pyif.tools.main"],
    "nav2-pyif-bench": ["-m", "nav2_pyif_bench.cli"],
}
#: planner-host with something to serve, so that only the option under test is wrong
HOST = ["planner-host", "--key", "k/a", "--planner", "echo_planners:EchoController"]


def command(argv: list[str], env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    environ = {k: v for k, v in os.environ.items() if not k.startswith("NAV2_PYIF_")}
    environ["PYTHONPATH"] = os.pathsep.join([str(FIXTURES), os.environ.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, *COMMANDS[argv[0]], *argv[1:]],
        capture_output=True,
        text=True,
        timeout=60,
        env={**environ, **(env or {})},
    )


def assert_usage_error(done: subprocess.CompletedProcess[str], *words: str) -> None:
    assert done.returncode == 2, done.stderr
    assert "usage:" in done.stderr and "Traceback" not in done.stderr, done.stderr
    assert "ZError" not in done.stderr, done.stderr
    for word in words:
        assert word in done.stderr, done.stderr


ENDPOINT_FORM = "tcp/HOST:PORT"


@pytest.mark.parametrize(
    ("argv", "env", "named"),
    [
        ([*HOST, "--connect", "bogus"], {}, "argument --connect: 'bogus'"),
        ([*HOST, "--listen", "tcp/127.0.0.1"], {}, "argument --listen: 'tcp/127.0.0.1'"),
        (HOST, {"NAV2_PYIF_CONNECT": "localhost:7447"}, "NAV2_PYIF_CONNECT='localhost:7447'"),
        (HOST, {"NAV2_PYIF_LISTEN": "tcp/[::1]:99999"}, "NAV2_PYIF_LISTEN="),
        (["nav2-pyif", "router", "--listen", "bogus"], {}, "nav2-pyif router: error: argument"),
        (["nav2-pyif", "sim", "--connect", "localhost:7447"], {}, "nav2-pyif sim: error"),
        (["nav2-pyif", "reload", "--key", "k/a", "--connect", "x/y:1"], {}, "unknown Zenoh"),
        (["nav2-pyif", "hosts", "--connect", "tcp/h:port"], {}, "argument --connect"),
        (["nav2-pyif-bench", "host", "--key", "k/a", "--connect", "bogus"], {}, "--connect"),
    ],
)
def test_a_malformed_endpoint_is_a_usage_error_naming_the_form(
    argv: list[str], env: dict[str, str], named: str
) -> None:
    assert_usage_error(command(argv, env), named, ENDPOINT_FORM.split(":")[0])


@pytest.mark.parametrize(
    "text",
    [
        "tcp/127.0.0.1:7447",
        "tcp/localhost:0",
        "tcp/[::1]:7447",
        "udp/224.0.0.224:7446#iface=lo",
        "tls/router.example.com:7447?prio=1",
        "quic/10.0.0.1:7447",
        "ws/host:80",
        "unixsock-stream//tmp/zenoh.sock",
    ],
)
def test_well_formed_endpoints_pass_and_zenoh_takes_them(text: str) -> None:
    assert endpoint(text) == text
    zenoh.Config().insert_json5("connect/endpoints", json.dumps([text]))  # Zenoh agrees


@pytest.mark.parametrize(
    "text", ["bogus", "localhost:7447", "tcp/", "/x", "tcp/host", "tcp/host:70000", "tcp/:7447"]
)
def test_malformed_endpoints_are_refused_by_the_check(text: str) -> None:
    with pytest.raises(argparse.ArgumentTypeError, match="tcp/"):
        endpoint(text)


def test_a_zenoh_config_file_is_checked_before_a_worker_starts(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json5"
    bad.write_text('{mode: "peer", connect: {endpoints: ["localhost:7447"]}}')
    missing = str(tmp_path / "missing.json5")
    for argv, env, words in [
        ([*HOST, "--zenoh-config", missing], {}, ("--zenoh-config", "does not exist")),
        (HOST, {"NAV2_PYIF_ZENOH_CONFIG": missing}, ("NAV2_PYIF_ZENOH_CONFIG=", "not exist")),
        ([*HOST, "--zenoh-config", str(bad)], {}, ("Zenoh cannot read", "localhost:7447")),
        (["nav2-pyif", "hosts"], {"NAV2_PYIF_ZENOH_CONFIG": missing}, ("$NAV2_PYIF_ZENOH_CONFIG",)),
        (["nav2-pyif", "router", "--zenoh-config", str(bad)], {}, ("Zenoh cannot read",)),
    ]:
        done = command(argv, env)
        assert_usage_error(done, *words)
        assert "worker" not in done.stderr, done.stderr  # nothing started


@pytest.mark.parametrize(
    ("argv", "env", "words"),
    [
        ([*HOST, "--deadline", "-1"], {}, ("argument --deadline", "> 0", "'-1'")),
        ([*HOST, "--deadline", "nan"], {}, ("argument --deadline", "> 0", "'nan'")),
        ([*HOST, "--plan-deadline", "inf"], {}, ("argument --plan-deadline", "> 0")),
        ([*HOST, "--hang-grace", "-1"], {}, ("argument --hang-grace", ">= 0")),
        ([*HOST, "--memory-limit", "-5"], {}, ("argument --memory-limit", "integer >= 0")),
        (HOST, {"NAV2_PYIF_HANG_GRACE": "-1"}, ("NAV2_PYIF_HANG_GRACE='-1'", ">= 0")),
        (HOST, {"NAV2_PYIF_MEMORY_LIMIT": "nan"}, ("NAV2_PYIF_MEMORY_LIMIT='nan'", "integer")),
        (["nav2-pyif", "sim", "--timeout", "-1"], {}, ("argument --timeout", "> 0")),
        (["nav2-pyif", "sim", "--timeout", "nan"], {}, ("argument --timeout", "> 0")),
        (["nav2-pyif", "sim", "--call-timeout", "-1"], {}, ("argument --call-timeout", "> 0")),
        (["nav2-pyif", "sim", "--scan-range", "-1"], {}, ("argument --scan-range", "> 0.05")),
        (["nav2-pyif", "sim", "--rate", "0"], {}, ("argument --rate", "> 0")),
        (["nav2-pyif", "sim", "--goal", "1", "nan", "0"], {}, ("argument --goal", "number")),
        (["nav2-pyif", "sim", "--scan-beams", "0"], {}, ("argument --scan-beams", ">= 1")),
        (["nav2-pyif", "reload", "--key", "k/a", "--timeout", "-1"], {}, ("--timeout", "> 0")),
        (["nav2-pyif", "hosts", "--wait", "nan"], {}, ("argument --wait", "> 0")),
        (["nav2-pyif", "learn", "--runs", "0"], {}, ("argument --runs", ">= 1")),
        (["nav2-pyif-bench", "fleet", "--robots", "10", "-1"], {}, ("--robots", ">= 1")),
        (["nav2-pyif-bench", "hops", "--rate", "0"], {}, ("argument --rate", "> 0")),
        (["nav2-pyif-bench", "protocol", "--seconds", "-3"], {}, ("--seconds", "> 0")),
    ],
)
def test_a_number_out_of_range_is_a_usage_error_naming_the_range(
    argv: list[str], env: dict[str, str], words: tuple[str, ...]
) -> None:
    assert_usage_error(command(argv, env), *words)


def test_the_host_still_serves_with_good_numbers(tmp_path: Path) -> None:
    """The checks refuse only what is wrong: 0 where 0 means something is taken."""
    port = free_port()
    host = subprocess.Popen(
        [
            sys.executable,
            *COMMANDS["planner-host"],
            *HOST[1:],
            "--listen",
            f"tcp/127.0.0.1:{port}",
            "--deadline",
            "0.5",
            "--hang-grace",
            "0",
            "--memory-limit",
            "0",
        ],
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": str(FIXTURES)},
    )
    try:
        assert host.stderr is not None
        for line in host.stderr:
            if "ready" in line or "error" in line:
                break
        assert "ready" in line, line
    finally:
        host.terminate()
        host.wait(15)
