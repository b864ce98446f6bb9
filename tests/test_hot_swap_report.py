"""A hot swap during a run shows in its report, JSON and PNG: each planner with the simulated
time it served, and the swap marked where the robot was (real host, real ``nav2-pyif sim``
process, a real ``reload`` between)."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from nav2_pyif.tools.admin import request_reload
from PIL import Image

pytestmark = pytest.mark.integration

KEY = "nav2_pyif/sim/FollowPath"


def test_a_hot_swap_during_a_run_is_on_its_report_and_picture(
    start_host: Any, zsession_factory: Any, tmp_path: Path
) -> None:
    host = start_host(
        *("--serve", f"{KEY}=nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"),
        *("--serve", "nav2_pyif/sim/GridBased=nav2_pyif_planners.astar:AStar"),
        *("--allow-remote-reload", "--reload-allow", "nav2_pyif_planners.*"),
    )
    sim = subprocess.Popen(
        [
            *(sys.executable, "-m", "nav2_pyif.tools.main", "sim", "--no-progress"),
            *("--connect", host.endpoint, "--realtime", "--out", str(tmp_path)),
            *("--call-timeout", "1"),  # a loaded machine must not end the run before the swap
            *("--start", "2", "2.5", "0", "--goal", "3.2", "5.5", "1.57"),  # about 8 s
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 60
        while "for controller_server/FollowPath" not in host.log():  # its session is live
            assert sim.poll() is None and time.monotonic() < deadline, host.log()
            time.sleep(0.1)
        time.sleep(2.0)  # driving by now, at real-time pace
        session = zsession_factory(host.endpoint)
        request_reload(session, KEY, module="nav2_pyif_planners.apf", timeout=30)
        out, err = sim.communicate(timeout=120)
    finally:
        if sim.poll() is None:
            sim.kill()
            sim.wait()
    assert sim.returncode in (0, 1), err
    assert "controller pure_pursuit (0.0-" in out and "then apf (" in out, out + err
    record = json.loads((tmp_path / "office_pure_pursuit.json").read_text())
    (swap,) = record["summary"]["hot_swaps"]
    assert swap["role"] == "controller" and swap["planner"] == "nav2_pyif_planners.apf (delegates)"
    assert 1.0 < swap["t_s"] < record["summary"]["sim_time_s"]
    with Image.open(tmp_path / "office_pure_pursuit.png") as png:
        assert "pure_pursuit → apf + astar" in png.info["Title"]
