"""The network the documents' commands run in (tests/private_network.py) is their own: a port
taken on this machine is free inside it, and nothing listening outside is reachable from it."""

from __future__ import annotations

import socket
import subprocess

import pytest

from tests.conftest import free_port, in_project_env
from tests.private_network import PrivateNetwork, port_is_free

pytestmark = pytest.mark.integration

PROBE = """
import socket, sys
port = int(sys.argv[1])
with socket.socket() as s:
    s.bind(("127.0.0.1", port)); s.listen()  # free in here
with socket.socket() as s:
    s.settimeout(5)
    try:
        s.connect(("127.0.0.1", port))
    except ConnectionRefusedError:
        print("refused")
"""


def test_a_port_taken_here_is_free_and_unreachable_inside() -> None:
    network = PrivateNetwork()
    why_not = network.open()
    if why_not is not None:
        pytest.skip(f"no network of the tests' own here: {why_not}")
    with socket.socket() as outside:
        outside.bind(("127.0.0.1", free_port()))
        outside.listen()
        port = outside.getsockname()[1]
        assert not port_is_free(port)
        try:
            done = subprocess.run(
                network.command(in_project_env(f"python -c '{PROBE}' {port}")),
                capture_output=True,
                text=True,
                timeout=60,
            )
        finally:
            network.close()
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "refused"  # bound in there, and our listener out of reach
