"""The suite's tiers (tests/tiers.py): every test module names exactly one, pytest knows each
marker, the fast tier's guard stops what a unit test must not do, and CI runs the whole suite
by README's command."""

from __future__ import annotations

import ast
import multiprocessing
import os
import re
import subprocess
from pathlib import Path

import pytest
import zenoh

from tests.conftest import ROOT
from tests.tiers import TIERS, unit_tier_only

pytestmark = pytest.mark.unit

TESTS = ROOT / "tests"


def tier_marks(node: ast.AST) -> list[str]:
    """The tiers named as ``pytest.mark.<tier>`` in the code under ``node`` (not in strings)."""
    return [
        mark.attr
        for mark in ast.walk(node)
        if isinstance(mark, ast.Attribute)
        and mark.attr in TIERS
        and ast.unparse(mark.value) == "pytest.mark"
    ]


def module_tiers(path: Path) -> list[str]:
    """The tier markers of a module's top-level ``pytestmark`` (one marker or a list)."""
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(
            isinstance(target, ast.Name) and target.id == "pytestmark" for target in node.targets
        ):
            return tier_marks(node.value)
    return []


def test_every_test_module_names_exactly_one_tier() -> None:
    modules = sorted(TESTS.glob("test_*.py"))
    assert len(modules) > 50  # the glob found the suite
    wrong = {m.name: module_tiers(m) for m in modules if len(module_tiers(m)) != 1}
    assert not wrong, (
        "each test module needs one module-level `pytestmark = pytest.mark.<tier>`, tier one "
        f"of {TIERS} (tests/tiers.py says which); these have {wrong}"
    )


def test_a_module_without_a_tier_is_reported(tmp_path: Path) -> None:
    bare = tmp_path / "test_bare.py"
    bare.write_text("import pytest\n\n\ndef test_x() -> None:\n    pass\n")
    two = tmp_path / "test_two.py"
    two.write_text("import pytest\n\npytestmark = [pytest.mark.unit, pytest.mark.nav2]\n")
    one = tmp_path / "test_one.py"
    one.write_text("import pytest\n\npytestmark = [pytest.mark.cpp, pytest.mark.timeout(9)]\n")
    assert (module_tiers(bare), module_tiers(two), module_tiers(one)) == (
        [],
        ["unit", "nav2"],
        ["cpp"],
    )


def test_pytest_registers_the_tiers_strictly(pytestconfig: pytest.Config) -> None:
    """pyproject.toml registers the tiers, and an unregistered (misspelt) marker is an error."""
    registered = [line.split(":")[0] for line in pytestconfig.getini("markers")]
    assert sorted(set(registered) & set(TIERS)) == sorted(TIERS)
    assert pytestconfig.option.strict_markers


def test_unit_modules_carry_no_other_tier_on_a_test() -> None:
    """A test in a unit module marked nav2 (say) would run in the fast tier all the same."""
    mixed = [
        f"{path.name}: {mark}"
        for path in sorted(TESTS.glob("test_*.py"))
        if module_tiers(path) == ["unit"]
        for mark in tier_marks(ast.parse(path.read_text(encoding="utf-8")))
        if mark != "unit"
    ]
    assert mixed == []


def test_the_guard_stops_sessions_and_processes_then_lets_go() -> None:
    attempts = {
        "opened a Zenoh session": lambda: zenoh.open(zenoh.Config()),
        "started a process ('true')": lambda: subprocess.run(["true"], check=False),
        "started a process ('sh')": lambda: subprocess.run("sh -c true", shell=True, check=False),
        "started a multiprocessing process": lambda: multiprocessing.Process(target=print).start(),
        "forked": os.fork,
        "ran 'true'": lambda: os.system("true"),
    }
    opened = zenoh.open
    with unit_tier_only():
        for words, attempt in attempts.items():
            with pytest.raises(pytest.fail.Exception, match=re.escape(words)):
                attempt()
        # a read-only look at the checkout is allowed
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True)
        assert head.returncode == 0
    assert zenoh.open is opened  # restored after the block


def test_a_unit_test_runs_under_the_guard() -> None:
    """tests/conftest.py wraps this module's tests (marked unit) in the guard by itself."""
    with pytest.raises(pytest.fail.Exception, match="mark its module integration"):
        subprocess.run(["true"], check=False)
    with pytest.raises(pytest.fail.Exception, match="opened a Zenoh session"):
        zenoh.open(zenoh.Config())


def test_ci_runs_readme_whole_suite_command() -> None:
    """.ci/run calls the very command README gives for the whole suite, with no arguments."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert re.search(r"^\./scripts/test\.sh +# the whole test suite$", readme, re.MULTILINE)
    commands = [
        line
        for line in (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
        if line.strip() and not line.startswith("#")
    ]
    assert commands[-1] == "exec ./scripts/test.sh"
