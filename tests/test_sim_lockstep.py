"""Lockstep, the runner's default: simulated time waits for the planner's reply, so a moment
of slowness (a loaded machine) changes nothing in the run; the time it took is reported
against the control period and the plugin's timeout. --realtime keeps the robot's rule: a
late reply fails its cycle. Real hosts over Zenoh, a controller that really sleeps."""

from __future__ import annotations

from typing import Any

import pytest
from nav2_pyif.runner.report import format_report, summary
from nav2_pyif.testing import drive

from tests.conftest import FIXTURES

pytestmark = pytest.mark.integration

# about 8 simulated seconds on the office map
TASK: dict[str, Any] = {"start": (2.0, 2.5, 0.0), "goal": (3.2, 5.5, 1.57)}
SLOW = "user_faults:SlowAtTimes"  # three cycles of 0.3 s
STALLS = "user_faults:HostStalls"  # its host stopped for 2.5 s: its 1 s lease lapses


def test_lockstep_drives_a_slow_controller_exactly_as_a_fast_one() -> None:
    fast = drive("pure_pursuit", **TASK)
    slow = drive(SLOW, path=[str(FIXTURES)], **TASK)
    assert slow.reached and not slow.controller_errors, format_report(slow)
    assert slow.trajectory == fast.trajectory  # the slowness changed nothing driven
    timing = summary(slow)["timing"]
    assert timing["mode"] == "lockstep"
    assert timing["call_timeout_ms"] == 40.0  # the plugin's default timeout
    assert timing["over_call_timeout"] >= 3 and timing["over_control_period"] >= 3
    assert timing["calls"] == slow.cycles  # one call per cycle driven
    assert "lockstep (simulated time waited for every reply)" in format_report(slow)
    assert "over the timeout (Nav2 would fail those cycles)" in format_report(slow)


def test_lockstep_waits_out_a_host_whose_lease_lapsed_on_a_starved_machine() -> None:
    fast = drive("pure_pursuit", **TASK)
    stalled = drive(STALLS, path=[str(FIXTURES)], **TASK)
    assert stalled.reached and not stalled.controller_errors, format_report(stalled)
    assert stalled.trajectory == fast.trajectory  # the stall changed nothing driven
    lapsed = [r for r in stalled.records if r.op == "compute_velocity_commands" and not r.ok]
    assert lapsed, "the host's lease never lapsed: the test stalled nothing"


def test_realtime_fails_the_cycles_whose_reply_came_late() -> None:
    slow = drive(SLOW, path=[str(FIXTURES)], realtime=True, call_timeout=0.25, **TASK)
    late = [e for e in slow.controller_errors if "got no reply" in e and "within 250 ms" in e]
    # its three slow cycles at least (a loaded machine may make more late: real time)
    assert len(late) >= 3, slow.controller_errors
    assert summary(slow)["timing"]["mode"] == "real time"
