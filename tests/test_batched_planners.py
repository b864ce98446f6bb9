"""The batched reference planners drive to the goal: two simulated robots (two offline
runners, ``nav2-pyif sim --connect``) share one batched planner host, their control cycles
served together by one jit-compiled call for all robots: the JAX MPPI's, and Nav2MPPI's."""

from __future__ import annotations

import json
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import pytest

pytestmark = [
    pytest.mark.integration,
    pytest.mark.skipif(
        find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])"
    ),
]

PLANNER_KEY = "nav2_pyif/fleet/GridBased"


def robot_key(name: str) -> str:
    return f"nav2_pyif/{name}/FollowPath"


def drive_robots(host: Any, names: list[str], out: Path, *extra: str) -> list[dict[str, Any]]:
    """One offline runner per robot, all at once against ``host``: their JSON records."""
    runs = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "nav2_pyif.tools.main",
                "sim",
                *("--connect", host.endpoint, "--wait", "60"),
                *("--controller-key", robot_key(name), "--planner-key", PLANNER_KEY),
                *("--name", name, "--out", str(out), "--timeout", "90"),
                *extra,
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        for name in names
    ]
    outputs = [run.communicate(timeout=600)[0] for run in runs]
    for run, output in zip(runs, outputs, strict=True):
        assert run.returncode == 0, output[-3000:] + host.log()[-3000:]
    return [json.loads((out / f"{name}.json").read_text()) for name in names]


def batch_info(host: Any, name: str) -> dict[str, Any]:
    """What `nav2-pyif hosts --json` says of the batch group serving ``name``'s key."""
    hosts = ["hosts", "--json", "--connect", host.endpoint]
    listed = subprocess.run(
        [sys.executable, "-m", "nav2_pyif.tools.main", *hosts],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert listed.returncode == 0, listed.stderr
    keys = [k for h in json.loads(listed.stdout)["hosts"] for k in h["keys"]]
    (key,) = [k for k in keys if k["key"] == robot_key(name)]
    batch: dict[str, Any] = key["batch"]
    return batch


@pytest.mark.parametrize(
    "controller",
    ["nav2_pyif_planners.mppi_jax:MPPIJax", "nav2_pyif_planners.mppi_nav2:Nav2MPPI"],
)
def test_two_robots_reach_the_goal_with_one_batched_jax_mppi(
    start_host: Any, tmp_path: Path, controller: str
) -> None:
    names = ["alpha", "beta"]
    host = start_host(
        *(f"--serve={robot_key(n)}={controller}" for n in names),
        f"--serve={PLANNER_KEY}=nav2_pyif_planners.astar:AStar",
        "--batch",
    )
    records = drive_robots(host, names, tmp_path, "--param", "fleet_size=2")
    for record in records:
        summary = record["summary"]
        assert summary["reached"] is True and summary["collisions"] == 0, summary
        assert summary["served"]["controller"] == controller
    batch = batch_info(host, names[0])
    assert batch["keys"] == sorted(robot_key(n) for n in names)
    # every cycle reached the batch gate (computed, or on an overloaded machine answered
    # "overloaded" uncomputed after waiting a control period), and the two robots' cycles
    # were served by fewer calls than cycles: they shared batches
    assert batch["cycles"] + batch["dropped"] >= sum(r["summary"]["cycles"] for r in records)
    assert batch["batches"] < batch["cycles"], batch
