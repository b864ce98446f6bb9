"""A second machine on this one: a network namespace joined to the root namespace by a veth
pair, for tests where a planner host's link is cut (its machine vanishes) and restored.
Standard library and pytest only: the Nav2 launch tests (bridge_plugin/test/nav2), which run
in the ROS environment without the project's packages, import it too."""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
from collections.abc import Iterator

import pytest

SUBNET = "10.231.7"  # only inside the tests' own namespace pairs


def _ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True, timeout=20)


class Link:
    """Namespace ``ns`` (the planner host's machine) joined to this one by a veth pair."""

    def __init__(self, subnet: str = SUBNET) -> None:
        tag = f"{os.getpid() % 100000}"
        self.subnet = subnet
        self.ns, self.outer, self.inner = f"pyif{tag}", f"pyif{tag}r", f"pyif{tag}h"

    def up(self) -> None:
        _ip("netns", "add", self.ns)
        _ip("link", "add", self.outer, "type", "veth", "peer", "name", self.inner)
        _ip("link", "set", self.inner, "netns", self.ns)
        _ip("addr", "add", f"{self.subnet}.1/30", "dev", self.outer)
        _ip("link", "set", self.outer, "up")
        for args in (
            ("addr", "add", f"{self.subnet}.2/30", "dev", self.inner),
            ("link", "set", self.inner, "up"),
            ("link", "set", "lo", "up"),
        ):
            _ip("netns", "exec", self.ns, "ip", *args)

    def cut(self) -> None:
        _ip("link", "set", self.outer, "down")

    def restore(self) -> None:
        _ip("link", "set", self.outer, "up")

    def down(self) -> None:
        subprocess.run(["ip", "netns", "del", self.ns], capture_output=True, timeout=20)
        subprocess.run(["ip", "link", "del", self.outer], capture_output=True, timeout=20)


@contextlib.contextmanager
def namespace_link(subnet: str = SUBNET) -> Iterator[Link]:
    """A Link, up; removed afterwards. Skips the test, saying why, where namespaces cannot be
    made (no iproute2, not root)."""
    if shutil.which("ip") is None:
        pytest.skip("network-namespace test skipped: the `ip` command (iproute2) is missing")
    link = Link(subnet)
    try:
        link.up()
    except (subprocess.CalledProcessError, OSError) as exc:
        link.down()
        detail = getattr(exc, "stderr", "") or str(exc)
        pytest.skip(f"network-namespace test skipped: cannot create namespaces here ({detail})")
    try:
        yield link
    finally:
        link.down()
