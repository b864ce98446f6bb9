"""Several hosts on one key (replicas): the plugin talks to one, fails over to another when it
dies, and re-sends its state there — without a failed call, so without a failed goal."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import nav2_pyif as api
import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif import Plan
from nav2_pyif.client import ControllerClient, Timeouts
from nav2_pyif.common.zenoh_config import connect_to

from tests.conftest import free_port, host_process, make_costmap
from tests.test_host_e2e import pose

pytestmark = pytest.mark.integration

KEY = "nav2_pyif/replicas/FollowPath"


def test_failover_to_a_replica_loses_no_call(tmp_path: Path) -> None:
    hosts = [
        host_process(
            free_port(),
            ["--key", KEY, "--planner", "echo_planners:EchoController"],
            tmp_path / f"h{i}.log",
        ).start()
        for i in range(2)
    ]
    session = connect_to([h.endpoint for h in hosts])
    client = ControllerClient(
        session, KEY, make_costmap(), timeouts=Timeouts(call=0.3, lifecycle=5, configure=20)
    )
    try:
        assert client.hosts.wait_for(lambda alive: len(alive) == 2, 30), [h.log() for h in hosts]
        client.configure()
        client.activate()
        client.set_plan(Plan(np.zeros((31, 3)), "odom"))
        pinned = client.host
        assert pinned is not None
        # only the pinned replica ran the planner so far
        configured = ["configured" in h.log() for h in hosts]
        assert sorted(configured) == [False, True]
        victim = hosts[configured.index(True)]

        results: list[tuple[bool, Any]] = []
        started = time.monotonic()
        killed = False
        while time.monotonic() - started < 3.0:
            if not killed and time.monotonic() - started > 1.0:
                victim.kill()
                killed = True
            try:
                cmd = client.compute_velocity_commands(pose(), Twist())
                results.append((True, cmd.twist.linear.x))
            except api.Nav2Error as exc:
                results.append((False, str(exc)))
            time.sleep(0.05)
        failed = [r for r in results if not r[0]]
        assert not failed, failed[:3]
        assert all(r[1] == 31 for r in results)  # the plan was re-sent to the new replica
        assert client.host != pinned and client.failovers == 1 and client.resyncs == 1
        survivor = hosts[1 - configured.index(True)]
        assert "configured" in survivor.log()
    finally:
        client.close()
        session.close()
        for host in hosts:
            if host.proc is not None and host.proc.poll() is None:
                host.stop()
