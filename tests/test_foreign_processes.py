"""The suite touches only what it started. Run last (tests/conftest.py orders it so): the
planner host and the Zenoh router on 7447 that were started beside the suite before its first
test, in process groups of their own (tests/neighbours.py), are still alive and were never
signalled, stopped or reloaded by it. And no document, test or script signals processes by
name, which reaches every process of that name on the machine (README's reload example sent
SIGHUP to every planner-host, other checkouts' included)."""

from __future__ import annotations

import re
import subprocess

import pytest

from tests.conftest import ROOT
from tests.neighbours import Neighbours

pytestmark = pytest.mark.integration

#: Commands that pick processes by name (pgrep only finds them, but to signal them next).
BY_NAME = re.compile(r"\b(pkill|killall|pgrep)\b")
#: Where commands are written: what users copy and what the tests and scripts run.
WHERE = ("README.md", "*.md", "docs", "tests", "scripts", "benchmarks", "docker", "bridge_plugin")


def test_nothing_signals_processes_by_name() -> None:
    listed = subprocess.run(
        ["git", "ls-files", "--", *WHERE], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout.split()
    found = []
    for name in sorted(set(listed) - {"tests/test_foreign_processes.py"}):
        try:
            text = (ROOT / name).read_text()
        except (UnicodeDecodeError, OSError):
            continue  # binary (images, vectors) or gone from the work tree
        found += [
            f"{name}:{number}: {line.strip()}"
            for number, line in enumerate(text.splitlines(), 1)
            if BY_NAME.search(line)
        ]
    assert not found, "signal what you started, by its pid:\n" + "\n".join(found)


def test_the_processes_beside_the_suite_are_alive_and_untouched(neighbours: Neighbours) -> None:
    assert neighbours.host is not None
    problems = neighbours.problems()
    assert not problems, "\n".join(problems) + f"\n{neighbours.note}"
