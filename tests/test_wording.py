"""What a reader of the project cannot look up stays out of it: the project's issue tracker is
private to its makers, so no file says "issue N" (or "issues N, M"), and the university
prototype the project grew from is named once, in README.md, and described in words elsewhere,
never called "the seed" or its paper. Every tracked text file is read; only this one is
exempt, for its examples of what the patterns catch (the project keeps no history file that
would have to quote old issue numbers: each CHANGELOG.rst says what changed, not which issue
asked for it)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.unit

ISSUE_NUMBER = re.compile(r"\bissues?\s+#?\d", re.IGNORECASE)
SEED = re.compile(r"\bseed(?:\s+paper|[- ]style|\s+YAML)\b|\bthe\s+seed's", re.IGNORECASE)
THIS_FILE = Path(__file__).resolve().relative_to(ROOT).as_posix()


def tracked_text_files() -> dict[str, str]:
    """Every tracked file that is UTF-8 text: path -> text."""
    listed = subprocess.run(
        ["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True
    ).stdout.decode()
    texts = {}
    for name in filter(None, listed.split("\0")):
        if name == THIS_FILE:
            continue
        try:
            texts[name] = (ROOT / name).read_text(encoding="utf-8")
        except (UnicodeDecodeError, FileNotFoundError, IsADirectoryError):
            continue  # binary (test vectors, images), or deleted in the work tree
    return texts


def offending_lines(pattern: re.Pattern[str]) -> list[str]:
    return [
        f"{name}:{number}: {line.strip()}"
        for name, text in tracked_text_files().items()
        for number, line in enumerate(text.splitlines(), 1)
        if pattern.search(line)
    ]


def test_the_patterns_catch_what_they_are_for() -> None:
    caught = [
        "Issue 15's targets",
        "(issue 12 item 6)",
        "as issues 3 and 4 asked",
        "see issue #27",
        "The seed paper's function-delegate style",
        "the seed's style",
        "(the seed's python_module)",
        "classes and seed-style functions",
        "the seed YAML's planner_host_command",
    ]
    kept = [
        "seed=3",
        "`seed` makes the noise reproducible",
        "issue() {  # issue NAME [subjectAltName]",
        "tests/fixtures/seed_layer.py",
        "test_nav2_seed_style.py",
    ]
    assert [s for s in caught if not (ISSUE_NUMBER.search(s) or SEED.search(s))] == []
    assert [s for s in kept if ISSUE_NUMBER.search(s) or SEED.search(s)] == []


def test_no_file_names_an_internal_issue_number() -> None:
    found = offending_lines(ISSUE_NUMBER)
    assert not found, "say what is meant instead of the issue's number:\n" + "\n".join(found)


def test_no_file_calls_the_prototype_the_seed() -> None:
    found = offending_lines(SEED)
    assert not found, (
        "describe the function-delegate style or the prototype in words (README.md names the "
        "thesis once):\n" + "\n".join(found)
    )
