"""free_port: the loopback port a test or benchmark gives a child to listen on is free and
outside the range the kernel hands out itself (where a Zenoh peer listening on port 0, or any
outgoing connection, could take it before the child binds it)."""

from __future__ import annotations

import random
import socket
from pathlib import Path

import pytest
from nav2_pyif.common.host_process import free_port

pytestmark = pytest.mark.unit


def ephemeral_range() -> tuple[int, int]:
    low, high = Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()
    return int(low), int(high)


def test_the_port_is_below_the_ephemeral_range_and_can_be_bound() -> None:
    for _ in range(20):
        port = free_port()
        assert 20000 <= port < ephemeral_range()[0]
        with socket.socket() as s:
            s.bind(("127.0.0.1", port))


def test_a_port_in_use_is_passed_over(monkeypatch: pytest.MonkeyPatch) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", free_port()))
        taken.listen()
        busy = taken.getsockname()[1]
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            spare = probe.getsockname()[1]  # freed when the probe closes
        draws = iter([busy, spare])
        monkeypatch.setattr(random, "randint", lambda _low, _high: next(draws))
        assert free_port() == spare
