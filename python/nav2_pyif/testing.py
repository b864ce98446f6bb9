"""Test your planners offline, with pytest, through a real planner host over Zenoh::

    from nav2_pyif.testing import assert_reaches_goal, drive

    def test_my_controller_reaches_the_goal():
        result = drive("my_pkg.ctrl:MyController", map="cluttered")
        assert_reaches_goal(result, min_clearance=0.05)

``drive`` takes the runner's options (``start``, ``goal``, ``rate``, ``timeout``,
``controller_params``, ...; see ``nav2_pyif.runner.run.SimConfig``) and returns a SimResult
with the outcome, the trajectory, the plan and every call's timing. It runs in lockstep:
simulated time waits for every reply, so a loaded machine does not change the verdict;
``result.timing`` counts the calls over the control period and the plugin's timeout
(``realtime=True`` fails those cycles instead, as on the robot).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.nav2_params import AUTO, sim_config
from nav2_pyif.runner.report import format_report
from nav2_pyif.runner.run import SimResult, run_sim


def drive(
    controller: str | None,
    planner: str | None = None,
    map: str | Path = "office",
    params_file: str | Path | None = AUTO,
    **options: Any,
) -> SimResult:
    """One navigation task on a bundled map (by name) or a map_server YAML. ``params_file``:
    a Nav2 params file whose controller_frequency, goal checker, nav2_pyif plugins (planner,
    parameters, timeouts) the run takes where not given here (default: ./nav2_params.yaml when
    present; None: none). A planner left None is the file's, else the runner's default."""
    config = sim_config(
        map_path(str(map)), params_file, controller=controller, planner=planner, **options
    )
    return run_sim(config)


def assert_reaches_goal(
    result: SimResult, *, min_clearance: float = 0.0, max_time: float | None = None
) -> None:
    """Fail with the run's report unless it reached the goal without collision, keeping
    ``min_clearance`` metres from obstacles, within ``max_time`` simulated seconds."""
    problems = []
    if not result.reached:
        problems.append(f"goal not reached ({result.outcome})")
    if result.collisions:
        problems.append(f"{result.collisions} collision(s)")
    if result.min_clearance < min_clearance:
        problems.append(f"clearance {result.min_clearance:.3f} m < {min_clearance} m")
    if max_time is not None and result.sim_time > max_time:
        problems.append(f"took {result.sim_time:.1f} s > {max_time} s")
    if problems:
        raise AssertionError("; ".join(problems) + "\n" + format_report(result))
