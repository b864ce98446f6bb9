"""``nav2-pyif eval --compare A B``: whether two evaluations agree on everything but the
compute figures, as two lockstep evaluations of deterministic planners must (one on an idle
machine, one under load)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from nav2_pyif.evaluation.metrics import COMPUTE_FIELDS
from nav2_pyif.evaluation.report import without_compute

REPORT = "eval.json"


class CompareError(ValueError):
    """A report that cannot be read (a usage error: exit 2)."""


def load_report(where: Path) -> dict[str, Any]:
    """The report in ``where`` (an --out directory or its eval.json)."""
    path = where / REPORT if where.is_dir() else where
    try:
        report = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise CompareError(f"{path} is not a readable eval report: {exc}") from exc
    if not isinstance(report, dict) or not {"summary", "runs", "settings"} <= set(report):
        raise CompareError(f"{path} is not an eval report (no summary, runs and settings)")
    return report


def _label(row: Any, index: int) -> str:
    """A row by its planner (and scenario), not its index: the reports' order may differ."""
    if not isinstance(row, dict) or "planner" not in row:
        return f"[{index}]"
    where = f" on {row['scenario']}" if "scenario" in row else ""
    return f"[{row['planner']}{where}]"


def _keyed(rows: list[Any]) -> dict[str, Any]:
    return {_label(row, i): row for i, row in enumerate(rows)}


def _joined(where: str, key: str) -> str:
    return f"{where}{key}" if key.startswith("[") or not where else f"{where}.{key}"


def differences(a: Any, b: Any, where: str = "") -> list[str]:
    """Every place where ``a`` and ``b`` differ, as 'where: a != b' lines."""
    if isinstance(a, dict) and isinstance(b, dict):
        lines = []
        for key in [*a, *(k for k in b if k not in a)]:
            if key not in a or key not in b:
                lines.append(f"{_joined(where, str(key))}: only in {'B' if key not in a else 'A'}")
            else:
                lines += differences(a[key], b[key], _joined(where, str(key)))
        return lines
    return [] if a == b else [f"{where}: {a!r} != {b!r}"]


def compare(a: dict[str, Any], b: dict[str, Any]) -> list[str]:
    """What differs between two reports, less the compute figures (and the worker count)."""
    a, b = without_compute(a), without_compute(b)
    for report in (a, b):
        for section in ("summary", "runs"):
            report[section] = _keyed(report[section])
    return differences(a, b)


def run_compare(first: Path, second: Path) -> int:
    """Print whether the reports agree; 0 when they do, 1 when they differ."""
    a, b = load_report(first), load_report(second)
    lines = compare(a, b)
    ignored = ", ".join((*COMPUTE_FIELDS, "settings.workers"))
    if lines:
        print(f"A ({first}) and B ({second}) differ in {len(lines)} place(s):")
        print("\n".join(f"  {line}" for line in lines))
        print(f"(not compared: {ignored})")
        return 1
    print(
        f"identical: {len(a['runs'])} run(s) of {len(a['summary'])} planner(s), "
        f"except the compute figures ({ignored})"
    )
    return 0
