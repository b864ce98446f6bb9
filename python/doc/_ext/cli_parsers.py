"""The commands' real argparse parsers, as sphinx-argparse's ``:func:`` wants them: a
function of no arguments returning one parser (the reference's commands page)."""

from __future__ import annotations

import argparse
import textwrap


def _as_shown_by_help(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Epilogs are laid out for a terminal (examples, a signals table): sphinx-argparse
    reads them as reStructuredText, so each becomes a literal block, shown as --help shows
    it. Subcommands' too."""
    if parser.epilog:
        parser.epilog = "::\n\n" + textwrap.indent(parser.epilog, "   ")
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                _as_shown_by_help(sub)
    return parser


def planner_host() -> argparse.ArgumentParser:
    from nav2_pyif.server.cli import build_parser

    return _as_shown_by_help(build_parser())


def nav2_pyif() -> argparse.ArgumentParser:
    from nav2_pyif.tools.main import build_parser

    parser, _ = build_parser()
    return _as_shown_by_help(parser)


def nav2_pyif_learn() -> argparse.ArgumentParser:
    from nav2_pyif_planners.learned.cli import parser

    return _as_shown_by_help(parser())


def nav2_pyif_bench() -> argparse.ArgumentParser:
    from nav2_pyif_bench.cli import build_parser

    return _as_shown_by_help(build_parser())
