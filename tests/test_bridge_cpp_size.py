"""The bridge README's count of hand-written C++ lines per role is the tree's count today.

A .cpp/.hpp under bridge_plugin/src or bridge_plugin/include is generated when its first line
is the generator's header (``// Generated from protocol/nav2_pyif_protocol/...``); every other
one is hand-written and belongs to the role its folder names. Print the table with
``python -m tests.test_bridge_cpp_size``.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.unit

BRIDGE = ROOT / "bridge_plugin"
README = BRIDGE / "README.md"
GENERATED = "// Generated from protocol/nav2_pyif_protocol/"
#: Each role's folders (relative to bridge_plugin/); a file belongs to the first that holds it.
ROLES = {
    "the codec's runtime": ("src/protocol", "include/nav2_pyif_bridge/protocol"),
    "the plugins' side of the protocol": ("src/client", "include/nav2_pyif_bridge/client"),
    "the Nav2 side": ("src/nav2", "include/nav2_pyif_bridge"),
}


def sources() -> list[Path]:
    return sorted(
        path
        for folder in ("src", "include")
        for path in (BRIDGE / folder).rglob("*")
        if path.suffix in (".cpp", ".hpp")
    )


def role_of(path: Path) -> str:
    relative = path.relative_to(BRIDGE).as_posix()
    return next(
        role
        for role, folders in ROLES.items()
        if any(relative.startswith(folder + "/") for folder in folders)
    )


def counts() -> dict[str, int]:
    """Lines per role, hand-written; "generated" for the generated files of every role."""
    out = dict.fromkeys([*ROLES, "generated"], 0)
    for path in sources():
        lines = path.read_text().splitlines()
        generated = bool(lines) and lines[0].startswith(GENERATED)
        out["generated" if generated else role_of(path)] += len(lines)
    return out


def number(n: int) -> str:
    """9987 -> "9 987", as the README writes numbers."""
    return f"{n:,}".replace(",", " ")


def test_every_source_has_a_role() -> None:
    for path in sources():
        assert role_of(path) in ROLES, path


def test_readme_counts_are_todays() -> None:
    readme = README.read_text()
    found = counts()
    for role, lines in found.items():
        row = re.search(rf"^\| {re.escape(role)}\b[^|]*\| ([0-9 ]+) \|", readme, re.MULTILINE)
        assert row, f"bridge README: no row for {role!r} in the table of hand-written lines"
        assert row.group(1) == number(lines), f"{role}: README {row.group(1)}, today {lines}"
    total = sum(n for role, n in found.items() if role != "generated")
    assert f"{number(total)} hand-written lines" in readme


def test_a_generated_file_says_so_first() -> None:
    """Only the generator's own header marks a file generated: a hand-written file that
    mentions generated code in its opening comment is still hand-written."""
    hand = BRIDGE / "src" / "protocol" / "reader.hpp"
    assert "generated" in hand.read_text()[:400] and not hand.read_text().startswith(GENERATED)
    for generated in ("body_codec.cpp", "envelopes.cpp"):
        assert (BRIDGE / "src" / "protocol" / generated).read_text().startswith(GENERATED)


if __name__ == "__main__":
    for role, lines in counts().items():
        print(f"{role}: {number(lines)}")
