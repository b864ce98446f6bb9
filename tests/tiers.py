"""The suite's tiers, one pytest marker each, and what keeps the fast one honest.

Every test module names its tier with a module-level ``pytestmark`` (tests/test_tiers.py
checks that each does):

- ``unit``: no Zenoh session, no child process (a read-only ``git`` query of the checkout
  aside), no build: the fast tier, ``./scripts/test.sh --fast``;
- ``integration``: real Zenoh sessions on loopback, real planner hosts or other processes;
- ``container``: podman images and containers;
- ``cpp``: builds and runs the C++ (the codec against the shared vectors, the unit tests);
- ``nav2``: needs a ROS 2 with Nav2 (skipped, saying so, where there is none).

A test marked ``unit`` that opens a Zenoh session or starts a process fails at that call,
saying which tier it belongs to (tests/conftest.py wraps each unit test's setup and call in
``unit_tier_only``).
"""

from __future__ import annotations

import multiprocessing.process
import os
import subprocess
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, NoReturn

import pytest
import zenoh

TIERS = ("unit", "integration", "container", "cpp", "nav2")


def _refuse(what: str) -> NoReturn:
    # pytest.fail raises an OutcomeException (a BaseException): no `except Exception` in the
    # code under test can swallow it.
    pytest.fail(f"a test marked unit {what}: mark its module integration (tests/tiers.py)")


def _argv0(args: Any) -> str:
    first = args if isinstance(args, str | bytes | os.PathLike) else next(iter(args), "")
    name = os.fsdecode(first).split()[0] if first else ""
    return os.path.basename(name)


@contextmanager
def unit_tier_only() -> Iterator[None]:
    """Within it, opening a Zenoh session or starting a process (other than ``git``) fails
    the test; undone when the block ends."""
    execute_child: Callable[..., Any] = subprocess.Popen._execute_child  # type: ignore[attr-defined]

    def guarded_execute_child(self: subprocess.Popen[Any], args: Any, *rest: Any) -> Any:
        if _argv0(args) != "git":
            _refuse(f"started a process ({_argv0(args)!r})")
        return execute_child(self, args, *rest)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(zenoh, "open", lambda *a, **k: _refuse("opened a Zenoh session"))
        patch.setattr(subprocess.Popen, "_execute_child", guarded_execute_child)
        patch.setattr(
            multiprocessing.process.BaseProcess,
            "start",
            lambda self: _refuse("started a multiprocessing process"),
        )
        patch.setattr(os, "fork", lambda: _refuse("forked"))
        patch.setattr(os, "system", lambda command: _refuse(f"ran {command!r}"))
        patch.setattr(os, "posix_spawn", lambda *a, **k: _refuse("spawned a process"))
        patch.setattr(os, "posix_spawnp", lambda *a, **k: _refuse("spawned a process"))
        yield
