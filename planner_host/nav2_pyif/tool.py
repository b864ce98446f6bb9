"""``nav2-pyif``: the project's command-line tools."""

from __future__ import annotations

import argparse
import logging
import sys

from nav2_pyif.sim.cli import add_sim_parser


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="nav2-pyif", description="nav2_pyif tools")
    subparsers = parser.add_subparsers(required=True, metavar="COMMAND")
    add_sim_parser(subparsers)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="[%(levelname)s] [%(name)s] %(message)s")
    code: int = args.func(args)
    return code


if __name__ == "__main__":
    sys.exit(main())
