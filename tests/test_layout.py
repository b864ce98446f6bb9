"""The package layout the site's architecture page describes, and the one-way imports it
promises, checked on the code itself: every import statement of every module (function-level
ones included)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

pytestmark = pytest.mark.unit

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "nav2_pyif"

#: Which part of nav2_pyif each part may import (besides itself, the protocol and third parties).
#: "api" is the top of nav2_pyif: what planner authors import.
MAY_IMPORT = {
    "api": {"api"},
    "common": set(),
    "server": {"api", "common"},
    "client": {"api", "common"},
    "runner": {"api", "client", "common"},
    "replay": {"api", "common", "server"},
    "tools": {"api", "client", "common", "runner", "replay"},
}
#: nav2_pyif.testing helps authors test their planners with the runner: it sits at the top for
#: them to import, and is nobody's dependency.
CONSUMERS_AT_THE_TOP = {"testing"}


def part_of(module: str) -> str:
    """The part a dotted module name under nav2_pyif belongs to."""
    parts = module.split(".")
    if len(parts) > 2 or (len(parts) == 2 and (PACKAGE / parts[1]).is_dir()):
        return parts[1]
    return "api"


def modules() -> list[tuple[str, Path]]:
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        name = ".".join(p for p in rel.parts if p != "__init__")
        found.append((name, path))
    return found


def imported(path: Path) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
    return names


def test_the_parts_are_the_readme_s() -> None:
    readme = (PACKAGE.parent / "doc" / "explanation" / "architecture.md").read_text()
    packages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    assert packages == set(MAY_IMPORT) - {"api"}
    for package in packages:
        assert f"`nav2_pyif.{package}`" in readme, f"the layout table misses {package}"


@pytest.mark.parametrize(("name", "path"), modules(), ids=[m for m, _ in modules()])
def test_imports_flow_one_way(name: str, path: Path) -> None:
    if name == "nav2_pyif" or name.removeprefix("nav2_pyif.") in CONSUMERS_AT_THE_TOP:
        allowed = set(MAY_IMPORT)
    else:
        allowed = MAY_IMPORT[part_of(name)] | {part_of(name)}
    for target in imported(path):
        assert not target.startswith("nav2_pyif_planners"), (
            f"{name} imports the reference planners ({target}): nav2_pyif names them by string"
        )
        if target == "nav2_pyif" or target.startswith("nav2_pyif."):
            assert part_of(target) in allowed, (
                f"{name} ({part_of(name)}) imports {target} ({part_of(target)})"
            )


def test_a_forbidden_import_is_caught(tmp_path: Path) -> None:
    """The checker itself: a server module importing the client is seen."""
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    from nav2_pyif.client import ControllerClient\n")
    assert part_of(next(iter(imported(bad)))) == "client"
    assert "client" not in MAY_IMPORT["server"]
