"""Nav2MPPI drives to the goal on both bundled maps through a real planner host (the
runner: Zenoh on loopback, the host in its own process), configured with Nav2 Jazzy's own
FollowPath MPPI block as its parameters."""

from __future__ import annotations

from importlib.util import find_spec

import pytest
from nav2_pyif.runner.maps import BUNDLED
from nav2_pyif.runner.report import format_report, summary
from nav2_pyif.testing import assert_reaches_goal, drive

pytestmark = [
    pytest.mark.integration,
    pytest.mark.skipif(
        find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])"
    ),
]


@pytest.mark.timeout(300)
@pytest.mark.parametrize("map_name", BUNDLED)
def test_nav2_mppi_block_drives_to_the_goal(map_name: str) -> None:
    from nav2_pyif_planners.mppi_nav2 import nav2_jazzy_params

    result = drive("mppi_nav2", map=map_name, controller_params=nav2_jazzy_params())
    print(format_report(result))  # the run's figures, shown with -s or on failure
    assert_reaches_goal(result, min_clearance=0.05, max_time=120.0)
    s = summary(result)
    assert 0.9 * s["plan_length_m"] < s["driven_distance_m"] < 1.2 * s["plan_length_m"]
    # Nav2's MPPI drives these at 0.34-0.46 m/s of its 0.5 (measured in the real Nav2); the
    # 4-term MPPIJax at 0.26-0.28
    assert s["driven_distance_m"] / s["sim_time_s"] > 0.35
