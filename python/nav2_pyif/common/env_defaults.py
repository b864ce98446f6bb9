"""Command-line options from environment variables, for containers (12-factor style).

Every long option ``--some-flag`` of a parser can be given as ``NAV2_PYIF_SOME_FLAG``; a flag on
the command line wins over the variable. Repeatable options take a comma-separated list
(``--path``: ``os.pathsep``-separated, as PATH), and flags given on the command line add to
that list. Switches (``store_true``) take 1/true/yes/on or 0/false/no/off. An empty variable
counts as unset (as compose's ``${VAR:-}`` leaves it), so ``NAV2_PYIF_CONFIG=`` does not
mean a file named "". A bad value is reported as a usage error naming the variable, before
anything starts.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Mapping
from typing import Any

PREFIX = "NAV2_PYIF_"
_TRUE = {"1", "true", "yes", "on"}
_FALSE = {"0", "false", "no", "off"}


def variable_name(option: str) -> str:
    """``--plan-deadline`` -> ``NAV2_PYIF_PLAN_DEADLINE``."""
    return PREFIX + option.lstrip("-").replace("-", "_").upper()


def _long_option(action: argparse.Action) -> str | None:
    longs = [s for s in action.option_strings if s.startswith("--")]
    return longs[0] if longs and longs[0] != "--help" else None


def document_environment(parser: argparse.ArgumentParser) -> None:
    """Name each option's variable in its help text, so --help shows both spellings."""
    for action in parser._actions:
        option = _long_option(action)
        if option is not None and action.help not in (None, argparse.SUPPRESS):
            action.help = f"{action.help} [env {variable_name(option)}]"


def _convert(parser: argparse.ArgumentParser, action: argparse.Action, name: str, text: str) -> Any:
    def one(item: str) -> Any:
        try:
            value = action.type(item) if callable(action.type) else item
        except (TypeError, ValueError, argparse.ArgumentTypeError) as exc:
            parser.error(f"{name}={text!r}: {exc}")
        if action.choices is not None and value not in action.choices:
            choices = ", ".join(map(str, action.choices))
            parser.error(f"{name}={text!r}: choose from {choices}")
        return value

    if isinstance(action, argparse._StoreTrueAction):
        if text.strip().lower() not in _TRUE | _FALSE:
            parser.error(f"{name}={text!r}: expected 1/true/yes/on or 0/false/no/off")
        return text.strip().lower() in _TRUE
    if isinstance(action, argparse._AppendAction):
        separator = os.pathsep if action.dest == "path" else ","
        # --delegate's own syntax is comma-separated ROLE=FUNCTION: one item holds them all.
        items = [text] if action.dest == "delegate" else text.split(separator)
        return [one(item.strip()) for item in items if item.strip()]
    return one(text)


def apply_environment(
    parser: argparse.ArgumentParser, environ: Mapping[str, str] | None = None
) -> dict[str, str]:
    """Set the parser's defaults from NAV2_PYIF_* variables; returns the variables used."""
    environ = os.environ if environ is None else environ
    used: dict[str, str] = {}
    defaults: dict[str, Any] = {}
    for action in parser._actions:
        option = _long_option(action)
        if option is None:
            continue
        name = variable_name(option)
        if environ.get(name, "").strip():
            defaults[action.dest] = _convert(parser, action, name, environ[name])
            used[name] = environ[name]
    parser.set_defaults(**defaults)
    return used
