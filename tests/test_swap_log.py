"""A hot swap says once that it configured each live session on the new planner, even when the
session changed while the new planner was taking it (a real host, a real reload)."""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
import pytest
from nav2_pyif import Plan
from nav2_pyif.tools.admin import request_reload

from tests.conftest import FIXTURES
from tests.test_host_e2e import KEY, controller

pytestmark = pytest.mark.integration


def test_a_swap_logs_each_session_configured_once(start_host: Any, zsession_factory: Any) -> None:
    host = start_host(
        *("--key", KEY, "--planner", "user_faults:SlowConfigure", "--path", str(FIXTURES)),
        "--allow-remote-reload",
    )
    client = controller(zsession_factory, host)
    client.configure()
    client.activate()
    client.set_plan(Plan(np.zeros((5, 3)), "odom"))
    reload = threading.Thread(
        target=request_reload, args=(zsession_factory(host.endpoint), KEY), kwargs={"timeout": 60}
    )
    reload.start()
    plans = 5
    while reload.is_alive():  # the session changes while the new planner configures
        client.set_plan(Plan(np.zeros((plans, 3)), "odom"))
        plans += 1
        reload.join(0.2)
    assert "session(s) carried over" in host.log(), host.log()
    configured = [line for line in host.log().splitlines() if "configured (epoch" in line]
    assert len(configured) == 2, configured  # the first configure, and the swap's
