"""Count each example's adapter lines, with the authors' helpers for adapters and without them.

A line is a non-blank line of code: not a comment, not a docstring. "With": the example's
adapter files as they are (the code between the library and nav2_pyif's API, imports
included). "Without": the same plus, for each helper the authors' API gained for adapters (the
geometry, obstacle points, the footprint's costs, the control period) that the adapter uses,
the lines of that helper's implementation in nav2_pyif (and of the helpers it calls), each
counted once: what the adapter had to carry before. A hand copy could be a little shorter; the
API's has the edge cases.

    python examples/adapter_size.py     # prints the table README.md shows
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parent
API = EXAMPLES.parent / "python" / "nav2_pyif"

#: example -> its adapter files (the rest of the example is the algorithm or the model)
ADAPTERS = {
    "ompl_planner": ["planner.py"],  # all of it glues OMPL to GlobalPlanner
    "casadi_mpc": ["controller.py"],  # problem.py is the MPC itself, in CasADi
    "onnx_policy": ["controller.py"],  # features.py and make_model.py make the model
    "dwa": ["controller.py", "rollout.py"],  # no library: the algorithm is the adapter
}
#: a helper for adapters as an adapter names it -> its implementation: (file, qualified name)
HELPERS = {
    "pose_xy_yaw": [("geometry.py", "pose_xy_yaw"), ("geometry.py", "yaw_of")],
    "wrap": [("geometry.py", "wrap")],
    "closest_index": [("geometry.py", "closest_index")],
    "carrot": [
        ("geometry.py", "carrot"),
        ("geometry.py", "closest_index"),
        ("geometry.py", "point_at_distance"),
    ],
    "obstacle_points": [("costmap.py", "Costmap.obstacle_points")],
    "circumscribed_cost": [
        ("costmap.py", "Costmap.circumscribed_cost"),
        ("costmap.py", "Costmap.inflation_cost"),
        ("costmap.py", "Costmap.inscribed_radius"),
        ("costmap.py", "Costmap.circumscribed_radius"),
        ("costmap.py", "Inflation.from_params"),  # the inflation layer's parameters
    ],
    "inscribed_radius": [("costmap.py", "Costmap.inscribed_radius")],
    "circumscribed_radius": [("costmap.py", "Costmap.circumscribed_radius")],
    "control_period": [("controller.py", "Controller.control_period")],
}


def docstring_lines(tree: ast.AST) -> set[int]:
    """The line numbers of every docstring in ``tree``."""
    lines: set[int] = set()
    for node in ast.walk(tree):
        if not isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef):
            continue
        first = node.body[0] if node.body else None
        if isinstance(first, ast.Expr) and isinstance(getattr(first.value, "value", None), str):
            lines.update(range(first.lineno, (first.end_lineno or first.lineno) + 1))
    return lines


def code_lines(path: Path, first: int = 1, last: int | None = None) -> int:
    """Lines of code of ``path`` from line ``first`` to ``last`` (1-based, inclusive)."""
    text = path.read_text().splitlines()
    skip = docstring_lines(ast.parse(path.read_text()))
    span = range(first, (last or len(text)) + 1)
    return sum(1 for n in span if n not in skip and text[n - 1].strip().split("#")[0].strip())


def definition(path: Path, qualname: str) -> ast.stmt:
    """The function (or property) ``qualname`` ("Class.method" or "function") in ``path``."""
    nodes: list[ast.stmt] = ast.parse(path.read_text()).body
    for part in qualname.split("."):
        found = next(n for n in nodes if getattr(n, "name", None) == part)
        nodes = getattr(found, "body", [])
    return found


def helpers_used(files: list[Path]) -> list[str]:
    names: set[str] = set()
    for path in files:
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Name):
                names.add(node.id)
            elif isinstance(node, ast.Attribute):
                names.add(node.attr)
    return sorted(names & set(HELPERS))


def measure(example: str) -> tuple[int, int, list[str]]:
    """(lines with the helpers, lines without them, the helpers used)."""
    files = [EXAMPLES / example / name for name in ADAPTERS[example]]
    now = sum(code_lines(path) for path in files)
    used = helpers_used(files)
    parts = {part for helper in used for part in HELPERS[helper]}
    before = now
    for file, qualname in sorted(parts):
        node = definition(API / file, qualname)
        first = min([node.lineno, *(d.lineno for d in getattr(node, "decorator_list", []))])
        before += code_lines(API / file, first, node.end_lineno)
    return now, before, used


def main() -> int:
    print("| example | adapter | lines with the helpers | without them | helpers used |")
    print("|---|---|---:|---:|---|")
    for example, files in ADAPTERS.items():
        now, before, used = measure(example)
        named = ", ".join(f"`{name}`" for name in files)
        print(f"| {example} | {named} | {now} | {before} | {', '.join(used)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
