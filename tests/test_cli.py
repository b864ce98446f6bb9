"""The planner-host command: help, clear errors with non-zero exits, clean shutdown."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
from nav2_pyif.server.cli import build_parser

from tests.conftest import FIXTURES
from tests.test_env_and_router import parse

pytestmark = pytest.mark.integration

PYTHONPATH = {"PYTHONPATH": str(FIXTURES)}


def run(*args: str, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    import os

    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif.server.cli", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=dict(os.environ, **PYTHONPATH),
    )


def test_help_lists_the_ways_to_serve() -> None:
    result = run("--help")
    assert result.returncode == 0
    for words in ("--planner MODULE:CLASS", "--delegate ROLE=FUNCTION", "--listen", "examples:"):
        assert words in result.stdout


def test_help_examples_are_valid_commands_that_fit_the_terminal() -> None:
    help_text = build_parser().format_help()
    examples = help_text.split("\nexamples:\n", 1)[1].split("\n\n")
    commands = [
        "".join(
            line.strip().removesuffix("\\")
            for line in block.splitlines()[1:]
            if not line.lstrip().startswith("#")  # a second comment line: not the command
        )
        for block in examples
        if block.lstrip().startswith("# ")
    ]
    assert len(commands) == 11
    for command in commands:
        words = shlex.split(command)
        assert "\\" not in command and all(w for w in words), command
        variables = [w for w in words if re.match(r"[A-Z][A-Z0-9_]*=", w)]
        assert words[len(variables)] == "planner-host", command
        environ = dict(v.split("=", 1) for v in variables)
        args = parse(environ, *words[len(variables) + 1 :])
        assert args.key or args.serve or args.config, command
    assert max(len(line) for line in help_text.splitlines()) <= 100


@pytest.mark.parametrize(
    ("args", "code", "words"),
    [
        (["--key", "k/a", "--planner", "no_such_mod:X"], 2, "No module named 'no_such_mod'"),
        (["--key", "k/a", "--planner", "echo_planners:Missing"], 2, "has no class 'Missing'"),
        (["--key", "k/a", "--planner", "broken_at_import:X"], 2, "fails at import on purpose"),
        (["--key", "k/*", "--planner", "echo_planners:LinePlanner"], 2, "wildcard"),
        (["--planner", "echo_planners:LinePlanner"], 2, "need --key"),
        ([], 2, "nothing to serve"),
        (
            ["--key", "k/a", "--module", "seed_delegates"],  # no function named after a role
            2,
            "module 'seed_delegates' defines none of compute_velocity_commands (a controller), "
            "create_plan (a global planner), smooth (a smoother), is_goal_reached (a goal "
            "checker), check (a progress checker) or update_costs (a costmap layer)",
        ),
        (
            ["--key", "k/a", "--module", "seed_delegates", "--delegate", "compute_velocity=c"],
            2,
            "unknown delegate role 'compute_velocity' (did you mean compute_velocity_commands?)"
            "; roles: activate, cancel, check, cleanup, compute_velocity_commands, configure, "
            "create_plan, deactivate, get_tolerances, is_goal_reached, match_size, reset, "
            "set_plan, set_speed_limit, smooth, update_bounds, update_costs",
        ),
        (
            [
                "--key",
                "k/a",
                "--planner",
                "echo_planners:LinePlanner",
                "--zenoh-config",
                "/nonexistent.json5",
            ],
            2,  # a usage error, before any worker starts
            "argument --zenoh-config: Zenoh config file '/nonexistent.json5' does not exist",
        ),
        (
            [
                *("--key", "k/a", "--planner", "echo_planners:EchoController", "--batch"),
                *("--batch-window", "20", "--control-period", "0.05"),
            ],
            2,  # the window may take at most a quarter of the control period
            "--batch-window: the batch window (20 ms) must lie between 0 and 0.25 x the "
            "control period (50 ms): at most 12.5 ms",
        ),
    ],
)
def test_bad_input_gets_a_clear_error(args: list[str], code: int, words: str) -> None:
    result = run(*args)
    assert result.returncode == code, result.stderr
    assert words in result.stderr


@pytest.mark.parametrize(
    ("entry", "words"),
    [
        ("{key: a/b}", "exactly one of planner / module"),
        (
            "{key: a/b, module: seed_delegates, delegates: {set_pln: on_plan}}",
            "planners[0]: unknown delegate role 'set_pln' (did you mean set_plan?); roles: ",
        ),
        (
            "{key: a/b, module: seed_delegates, delegates: [compute_velocity_commands=compute]}",
            "planners[0].delegates must map roles to functions",
        ),
    ],
)
def test_yaml_config(tmp_path: Path, entry: str, words: str) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text(f"planners:\n  - {entry}\n")
    result = run("--config", str(bad))
    assert result.returncode == 2 and words in result.stderr
