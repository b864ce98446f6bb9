"""Every console command (the pyproject.toml files' [project.scripts]) explains each of its
subcommands and options in --help, and checks its numbers."""

from __future__ import annotations

import argparse
import importlib
import inspect
import os
import re
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest
from nav2_pyif.plugin import PlannerPlugin
from nav2_pyif.server.loader import PLUGIN_BASES
from nav2_pyif.tools.main import PLANNERS_COMMANDS
from nav2_pyif_entry import TARGETS

from tests.conftest import FIXTURES, ROOT

pytestmark = pytest.mark.integration


def console_scripts() -> dict[str, str]:
    """name -> "module:function", from the [project.scripts] tables of the pyproject.toml of
    the core, the benchmarks and the code generators."""
    scripts: dict[str, str] = {}
    for folder in (ROOT, ROOT / "benchmarks", ROOT / "protocol" / "codegen"):
        pyproject = folder / "pyproject.toml"
        table = pyproject.read_text().split("[project.scripts]", 1)[1].split("\n[", 1)[0]
        scripts.update(re.findall(r'^([\w-]+)\s*=\s*"([\w.:]+)"', table, re.MULTILINE))
    return scripts


Named = tuple[str, argparse.ArgumentParser]  # a command line and its parser


class _Parsed(Exception):
    def __init__(self, parser: argparse.ArgumentParser) -> None:
        self.parser = parser


def parser_of(main: Any, monkeypatch: pytest.MonkeyPatch, *args: Any) -> argparse.ArgumentParser:
    """The parser a command's ``main`` builds: caught when it parses (nothing runs)."""

    def caught(self: argparse.ArgumentParser, *_: Any, **__: Any) -> Any:
        raise _Parsed(self)

    with monkeypatch.context() as patch:
        patch.setattr(argparse.ArgumentParser, "parse_known_args", caught)
        patch.setattr(argparse.ArgumentParser, "parse_args", caught)
        try:
            main([], *args)
        except _Parsed as parsed:
            return parsed.parser
    raise AssertionError(f"{main} parsed no arguments")


def every_parser(monkeypatch: pytest.MonkeyPatch) -> Iterator[Named]:
    """(command line, parser) for every console command and each of its subcommands; the
    commands that parse their own arguments (nav2-pyif learn) included."""
    scripts = console_scripts()
    assert {"planner-host", "nav2-pyif", "nav2-pyif-bench"} <= set(scripts), scripts
    for name, target in scripts.items():
        if target.startswith("nav2_pyif_entry:"):  # holds the signals, then runs the real main
            target = TARGETS[name]
        module, _, function = target.partition(":")
        main = getattr(importlib.import_module(module), function)
        yield from _walk(name, parser_of(main, monkeypatch))
    for name, (module, _) in PLANNERS_COMMANDS.items():
        main = importlib.import_module(module).main
        yield from _walk(f"nav2-pyif {name}", parser_of(main, monkeypatch, f"nav2-pyif {name}"))


def _walk(
    line: str, parser: argparse.ArgumentParser
) -> Iterator[tuple[str, argparse.ArgumentParser]]:
    yield line, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                if sub.add_help or name not in PLANNERS_COMMANDS:  # learn: its own parser
                    yield from _walk(f"{line} {name}", sub)


def _options(parser: argparse.ArgumentParser) -> Iterator[tuple[str, argparse.Action]]:
    for action in parser._actions:
        if not isinstance(action, argparse._HelpAction | argparse._SubParsersAction):
            yield "/".join(action.option_strings) or action.dest, action


def test_every_subcommand_and_option_of_every_command_has_help(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    missing = []
    seen = 0
    for line, parser in every_parser(monkeypatch):
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                helped = {a.dest: a.help for a in action._choices_actions}
                missing += [f"{line} {n}" for n in action.choices if not helped.get(n)]
        for name, action in _options(parser):
            seen += 1
            if not action.help or action.help == argparse.SUPPRESS:
                missing.append(f"{line} {name}")
    assert seen > 100  # the walk reached every command's options
    assert not missing, "no help text: " + ", ".join(missing)


def test_every_numeric_option_is_checked(monkeypatch: pytest.MonkeyPatch) -> None:
    """No bare int or float: each takes a range from nav2_pyif.common.option_types."""
    bare = [
        f"{line} {name}"
        for line, parser in every_parser(monkeypatch)
        for name, action in _options(parser)
        if action.type in (int, float)
    ]
    assert not bare, "numbers taken unchecked: " + ", ".join(bare)


def tool(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", *args],
        capture_output=True,
        text=True,
        timeout=60,
    )


@pytest.mark.parametrize(
    "command",
    [
        "nav2-pyif sim",
        "nav2-pyif reload --key k/a",
        "nav2-pyif hosts",
        "nav2-pyif router",
        "nav2-pyif-bench fleet",
        "nav2-pyif-bench host --key k/a",
    ],
)
def test_an_unknown_option_shows_the_command_s_own_usage(command: str) -> None:
    module = {"nav2-pyif": "nav2_pyif.tools.main", "nav2-pyif-bench": "nav2_pyif_bench.cli"}
    program, name, *args = command.split()
    done = subprocess.run(
        [sys.executable, "-m", module[program], name, *args, "--bogus"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith(f"usage: {program} {name} "), done.stderr
    assert f"{program} {name}: error: unrecognized arguments: --bogus" in done.stderr


def test_sim_help_explains_the_goal_and_each_plugin_s_parameters() -> None:
    done = tool("sim", "--help")
    assert done.returncode == 0, done.stderr
    text = re.sub(r"\s+", " ", done.stdout)
    assert "--goal X Y YAW goal pose" in text
    for flag in ("planner", "smoother", "goal-checker", "progress-checker", "layer"):
        assert re.search(rf"--{flag}-param NAME=VALUE \w", text), flag


def test_sim_help_shows_every_default_and_what_the_simulator_does() -> None:
    """Each option with a value shows its default (the call timeout's included), and the
    simulator's hidden facts are in --help: the goal check's heading tolerance, the rolling
    window, the control period, the inflation's threshold."""
    done = tool("sim", "--help")
    assert done.returncode == 0, done.stderr
    text = re.sub(r"\s+", " ", done.stdout)
    for option, default in [
        ("--call-timeout SECONDS", "the params file's timeout, else 0.04"),
        ("--rate RATE", "the params file's, else 20"),
        ("--timeout SECONDS", "180.0"),
        ("--plans N", "1"),
        ("--map MAP", "office"),
        ("--scan-beams SCAN_BEAMS", "360"),
        ("--max-recoveries N", "3"),
    ]:
        shown = re.search(rf"{re.escape(option)} .*?\(default: ([^)]+)\)", text)
        assert shown and shown.group(1) == default, (option, text)
    for fact in (
        "on the plan's last pose): within 0.25 m of it AND 0.25 rad of its heading",
        "a 5 m x 5 m rolling window about the robot, updated at 5 Hz",
        "control_period is 1 / --rate",
        "cost_scaling_factor 3",
        "circumscribed_cost() = 186",
    ):
        assert fact in text, fact


def test_the_plugin_bases_are_every_kind_a_planner_can_be() -> None:
    """planner-host's --planner help and its not-a-subclass error name each base class."""
    import nav2_pyif

    bases = {
        name
        for name, value in vars(nav2_pyif).items()
        if inspect.isclass(value) and PlannerPlugin in value.__bases__
    }
    assert bases == set(PLUGIN_BASES)
    host = [sys.executable, "-m", "nav2_pyif.server.cli"]
    shown = subprocess.run([*host, "--help"], capture_output=True, text=True, timeout=60)
    assert all(name in re.sub(r"\s+", "", shown.stdout) for name in PLUGIN_BASES), shown.stdout
    wrong = subprocess.run(
        [*host, "--key", "k/a", "--planner", "echo_planners:api"],  # a module, not a class
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "PYTHONPATH": str(FIXTURES)},
    )
    assert wrong.returncode == 2, wrong.stderr
    assert "not a nav2_pyif " in wrong.stderr
    assert all(name in wrong.stderr for name in PLUGIN_BASES), wrong.stderr
