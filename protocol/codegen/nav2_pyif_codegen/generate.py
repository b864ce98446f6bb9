"""Generate, from the one description of the protocol (``schema``, ``constants``), the files
that repeat it: the C++ message structs and their codec, the plugin types and nav2_core error
tables, the plugin's own parameters (``bridge_params``) and its default Zenoh config
(bridge_plugin/), PROTOCOL.md's field tables and the bridge README's parameter table.

    python -m nav2_pyif_codegen.generate            # rewrite them after editing schema.py
    python -m nav2_pyif_codegen.generate --check    # exit 1, naming each file, if stale
    python -m nav2_pyif_codegen.generate --out DIR  # write them below DIR instead

The generated files are checked in (review them with the schema edit); a test regenerates
them and fails on any difference. The Python codec needs no generated file: it compiles its
validators from the schema when it is imported.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from nav2_pyif_codegen import (
    cpp_codec,
    cpp_envelopes,
    cpp_errors,
    cpp_params,
    spec_tables,
    zenoh_copy,
)

#: The repository this package lives in (protocol/codegen/nav2_pyif_codegen/ -> the repository).
REPOSITORY = Path(__file__).resolve().parents[3]
PROTOCOL_MD = "protocol/PROTOCOL.md"
COMMAND = cpp_codec.COMMAND


def render(repository: Path = REPOSITORY) -> dict[str, str]:
    """Path (from the repository root) -> its generated text. PROTOCOL.md keeps its prose:
    only the part between its schema-table markers is generated; so does the bridge README,
    but for its parameter table."""
    out = (
        cpp_codec.files()
        | cpp_envelopes.files()
        | cpp_errors.files()
        | cpp_params.files()
        | zenoh_copy.files()
    )
    out[PROTOCOL_MD] = spec_tables.splice((repository / PROTOCOL_MD).read_text())
    out[cpp_params.README] = cpp_params.splice_readme((repository / cpp_params.README).read_text())
    return out


def stale(repository: Path = REPOSITORY) -> list[str]:
    """The generated files that differ from (or are missing in) ``repository``."""
    return [
        path
        for path, text in render(repository).items()
        if not (repository / path).is_file() or (repository / path).read_text() != text
    ]


def write(target: Path, repository: Path = REPOSITORY) -> list[str]:
    """Write every generated file below ``target``; returns the paths whose text changed."""
    changed = []
    for path, text in render(repository).items():
        file = target / path
        if file.is_file() and file.read_text() == text:
            continue
        file.parent.mkdir(parents=True, exist_ok=True)
        file.write_text(text)
        changed.append(path)
    return changed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m nav2_pyif_codegen.generate",
        description="Generate the C++ codec and PROTOCOL.md's field tables from schema.py.",
    )
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--check", action="store_true", help="exit 1 if a file is out of date")
    group.add_argument("--out", type=Path, metavar="DIR", help="write below DIR, not in place")
    parser.add_argument(
        "--repository",
        type=Path,
        default=REPOSITORY,
        metavar="DIR",
        help="the nav2_pyif checkout (default: the one this package is in)",
    )
    args = parser.parse_args(argv)
    if args.check:
        problems = stale(args.repository)
        for path in problems:
            print(f"out of date: {path} (run: {COMMAND})", file=sys.stderr)
        print(f"{len(render(args.repository)) - len(problems)} generated files up to date")
        return 1 if problems else 0
    changed = write(args.out or args.repository, args.repository)
    for path in changed:
        print(f"wrote {path}")
    print(f"{len(changed)} of {len(render(args.repository))} generated files changed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
