"""The gallery how-to's adapter sizes of examples/ are what examples/adapter_size.py counts
today, and the count is of code: docstrings, comments and blank lines are left out."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path
from types import ModuleType

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.unit


def counter() -> ModuleType:
    spec = importlib.util.spec_from_file_location(
        "adapter_size", ROOT / "examples" / "adapter_size.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_readme_shows_the_sizes_counted_today(capsys: pytest.CaptureFixture[str]) -> None:
    assert counter().main() == 0
    table = capsys.readouterr().out
    assert table.count("\n") == 6  # the header, its rule, four examples
    readme = (ROOT / "python" / "doc" / "howto" / "library_planner.md").read_text()
    assert table in readme
    for row in table.splitlines()[2:]:  # and the sentence that quotes them
        now, before = (cell.strip() for cell in row.split("|")[3:5])
        assert re.search(rf"\b{now}( lines)? \({before}\b", readme), row


def test_only_code_lines_count(tmp_path: Path) -> None:
    source = tmp_path / "adapter.py"
    source.write_text(
        '"""A module docstring\n\nover three lines."""\n\n'
        "import math  # a comment after code\n"
        "# a comment line\n\n"
        "def f(x):\n"
        '    """One line."""\n'
        "    return math.sqrt(\n"
        "        x\n"
        "    )\n"
    )
    assert counter().code_lines(source) == 5  # import, def, return, x, )
    assert counter().code_lines(source, 8, 9) == 1  # def f, not its docstring
