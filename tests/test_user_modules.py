"""A user's planner module, in the user's own directory (the first tutorial's my_planners/go_to.py,
taken from the tutorial itself), is found wherever a planner is named: ``scripts/sim.sh`` and
``nav2-pyif sim`` run from that directory or given ``--path``, and the pytest helper run from
another directory."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

from tests.conftest import ROOT, in_project_env
from tests.docs_blocks import blocks

pytestmark = pytest.mark.integration

SPEC = "my_planners.go_to:GoTo"
USER_FILE = "my_planners/go_to.py"
TUTORIAL = ROOT / "python" / "doc" / "tutorials" / "first_controller.md"


@pytest.fixture
def user_dir(tmp_path: Path) -> Path:
    """A directory holding the first tutorial's my_planners/go_to.py, outside the repository."""
    (block,) = [b for b in blocks(TUTORIAL, ROOT) if b.user_file == USER_FILE]
    target = tmp_path / "project" / USER_FILE
    target.parent.mkdir(parents=True)
    target.write_text(block.text)
    return tmp_path / "project"


def bash(command: str, cwd: Path, timeout: float = 300) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run(
        in_project_env(command),
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        env=env,
    )


def reached(record: Path) -> bool:
    return bool(json.loads(record.read_text())["summary"]["reached"])


def test_sim_script_imports_the_planner_from_the_callers_directory(user_dir: Path) -> None:
    result = bash(
        f"{ROOT}/scripts/sim.sh --map cluttered --controller {SPEC} --no-progress", user_dir
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert reached(user_dir / "out" / f"cluttered_{SPEC.replace(':', '.')}.json")


def test_sim_path_option_finds_the_planner_from_elsewhere(user_dir: Path, tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    result = bash(
        f"nav2-pyif sim --path {user_dir} --controller {SPEC} --no-progress --name run", elsewhere
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert reached(elsewhere / "out" / "run.json")


def test_pytest_helper_run_from_another_directory(user_dir: Path, tmp_path: Path) -> None:
    (user_dir / "test_go_to.py").write_text(
        "from nav2_pyif.testing import assert_reaches_goal, drive\n\n\n"
        "def test_go_to() -> None:\n"
        f"    assert_reaches_goal(drive({SPEC!r}, map='office'), min_clearance=0.05)\n"
    )
    # pytest puts the test file's directory on its sys.path; the host it starts must see it.
    result = bash(f"python -m pytest -q -p no:cacheprovider {user_dir}/test_go_to.py", tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
