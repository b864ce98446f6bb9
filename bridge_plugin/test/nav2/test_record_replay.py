"""A Nav2 run recorded by the planner host (planner-host --record) replays offline.

controller_server and planner_server with the nav2_pyif plugins drive the simulated robot to
a goal (Python A* and regulated pure pursuit) while the host records every call to MCAP; the
host then stops (SIGTERM: it closes the recording), and `nav2-pyif replay` feeds the
recording to the same planners: every output is the recorded one. The recording is kept in
the test's logs (nav2_run.mcap), and copied to $NAV2_PYIF_RECORDING_OUT when set
(tests/fixtures/nav2_launch_run.mcap, which tests/test_record_replay.py replays in every run
of the suite, was made so: Jazzy 1.3.8, zenoh-pico, 2026-12-02).

Needs what test_nav2_pyif.py needs, and `nav2-pyif` (through $NAV2_PYIF_RUN or on PATH).
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_testing
import pytest

GOAL = (2.0, 0.5)  # behind the wall: the plan goes around it


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    logs = tmp_path_factory.mktemp("nav2_record_replay")
    recording = logs / "nav2_run.mcap"
    planners = (*nav2_testing.REFERENCE_PLANNERS, "--record", str(recording))
    for nav2 in nav2_testing.bring_up(logs, planners=planners):
        yield dict(nav2, recording=recording)


def test_a_recorded_nav2_run_replays_identically(nav2: dict[str, Any]) -> None:
    client, procs = nav2["client"], nav2["procs"]
    servers = nav2_testing.SERVERS
    states = client.wait_active(servers, 90.0)
    assert all(s == "active" for s in states.values()), procs.log("planner_host")
    planned = client.plan(*GOAL)
    assert planned is not None and planned.status == nav2_testing.SUCCEEDED, procs.log(
        "planner_server"
    )
    result = client.wait(client.follow(planned.result.path).get_result_async(), 90.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == nav2_testing.SUCCEEDED, logs

    procs.kill("planner_host", signal.SIGTERM)  # waits: the recording is closed
    recording: Path = nav2["recording"]
    assert "recording: " in procs.log("planner_host") and recording.is_file(), logs
    if os.environ.get("NAV2_PYIF_RECORDING_OUT"):
        shutil.copyfile(recording, os.environ["NAV2_PYIF_RECORDING_OUT"])

    command = nav2_testing.project_command("nav2-pyif")
    assert command is not None, "nav2-pyif is not on PATH (or $NAV2_PYIF_RUN)"
    out = nav2["logs"] / "replay"
    done = subprocess.run(
        [*command, "replay", str(recording), "--out", str(out), "--isolation", "none"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads((out / "nav2_run_replay.json").read_text())["summary"]
    follow = summary["by_key"][f"{nav2_testing.PREFIX}/FollowPath"]
    assert follow["compute_velocity_commands"]["calls"] > 10, done.stdout
    assert summary["by_key"][f"{nav2_testing.PREFIX}/GridBased"]["create_plan"]["calls"] >= 1
    assert summary["errors"] == 0 and summary["identical"] == summary["calls"], done.stdout
