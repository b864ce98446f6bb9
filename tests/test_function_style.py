"""The function-delegate style works wherever the class style does: a user's own
module of plain functions, outside the repository, drives offline with one command —
``nav2-pyif sim --controller my_funcs:steer --planner my_funcs:bfs``, the module form
``--controller my_funcs``, and ``nav2_pyif.testing.drive`` — its functions get the goal's
tolerances, the plan, the control period and the cancel checker as keyword arguments, the
planner picks its threshold with ``costmap.circumscribed_cost()`` (the inflation the runner
applies, told in configure), and no warning names a role the user never bound."""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest
from nav2_pyif.testing import assert_reaches_goal, drive

from tests.test_user_modules import bash

pytestmark = pytest.mark.integration

#: A controller and a planner as plain functions: the main ones under names of the user's
#: choosing (module:function), and again under the roles' names (the module form).
MODULE = textwrap.dedent(
    '''\
    import math
    from collections import deque

    import numpy as np
    from geometry_msgs.msg import TwistStamped
    from nav2_pyif import (
        NoValidControl,
        NoValidPathCouldBeFound,
        PlannerCancelled,
        carrot,
        pose_xy_yaw,
        wrap,
    )

    calls = {"plans": 0}


    def steer(costmap, pose, twist, *, plan, goal_checker, control_period):
        """Carrot following, then a turn on the spot to the goal's heading."""
        if plan is None or goal_checker is None or control_period is None:
            raise NoValidControl(f"plan {plan}, tolerances {goal_checker}, dt {control_period}")
        x, y, yaw = pose_xy_yaw(pose)
        gx, gy, gyaw = plan.xy_yaw[-1]
        cmd = TwistStamped(header=pose.header)
        if math.hypot(gx - x, gy - y) < 0.5 * goal_checker.xy_goal_tolerance:
            error = wrap(gyaw - yaw)  # the goal check wants the heading too
        else:
            (cx, cy), _ = carrot(plan.xy_yaw, x, y, 0.4)
            error = wrap(math.atan2(cy - y, cx - x) - yaw)
            cmd.twist.linear.x = 0.4 * max(0.0, math.cos(error))
        # the heading error closed over five control periods
        cmd.twist.angular.z = float(np.clip(error / (5 * control_period), -1.5, 1.5))
        return cmd


    def bfs(costmap, start, goal, *, cancel_checker):
        """Breadth-first search over the cells that cannot touch the robot at any heading."""
        calls["plans"] += 1
        if calls["plans"] == 2:
            raise NoValidPathCouldBeFound("the second plan fails, to be timed in a row apart")
        free = (costmap.data < costmap.circumscribed_cost()).ravel()
        w = costmap.size_x
        (sx, sy), (gx, gy) = (costmap.world_to_map(*pose_xy_yaw(p)[:2]) for p in (start, goal))
        s, g = sy * w + sx, gy * w + gx
        came = np.full(free.size, -1)
        came[s] = s
        queue = deque([s])
        while queue and came[g] < 0:
            if len(queue) % 1000 == 0 and cancel_checker():
                raise PlannerCancelled("cancelled")
            c = queue.popleft()
            for d in (-1, 1, -w, w, -w - 1, -w + 1, w - 1, w + 1):
                n = c + d
                if 0 <= n < free.size and came[n] < 0 and free[n] and abs(n % w - c % w) <= 1:
                    came[n] = c
                    queue.append(n)
        if came[g] < 0:
            raise NoValidPathCouldBeFound("no free cells lead to the goal")
        cells = [g]
        while cells[-1] != s:
            cells.append(int(came[cells[-1]]))
        cells = np.array(cells[::-1])[::4].tolist() + [g]
        xy = costmap.map_to_world_array(np.column_stack(np.divmod(cells, w)[::-1]))
        yaw = np.append(np.arctan2(np.diff(xy[:, 1]), np.diff(xy[:, 0])), pose_xy_yaw(goal)[2])
        return np.column_stack([xy, yaw])


    compute_velocity_commands = steer  # the module form binds the roles' names
    create_plan = bfs
    '''
)


@pytest.fixture
def user_dir(tmp_path: Path) -> Path:
    project = tmp_path / "project"
    project.mkdir()
    (project / "my_funcs.py").write_text(MODULE)
    return project


def test_module_function_form_drives_with_one_command_timing_plans(user_dir: Path) -> None:
    """``module:function`` for both roles, from the user's directory, one command; --plans 3
    times create_plan three times, the failed one in a row of its own; configure has a row
    per plugin; the output is named after both; the host warns about nothing."""
    result = bash(
        "nav2-pyif sim --controller my_funcs:steer --planner my_funcs:bfs --plans 3 --no-progress",
        user_dir,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "create_plan timed 3 times (1 failed)" in result.stdout
    out = user_dir / "out"
    record = json.loads((out / "office_my_funcs.steer_my_funcs.bfs.json").read_text())
    assert record["summary"]["reached"]
    rows = {row["op"]: row["calls"] for row in record["latency"]}
    assert rows["create_plan"] == 2 and rows["create_plan FAILED"] == 1, rows
    assert rows["configure (controller)"] == 1 and rows["configure (planner)"] == 1, rows
    assert "configure" not in rows
    host_log = (out / "office_my_funcs.steer_my_funcs.bfs.host.log").read_text()
    assert "steer bound to compute_velocity_commands" in host_log
    assert "bfs bound to create_plan" in host_log
    assert "[WARNING]" not in host_log, host_log


def test_the_module_form_serves_one_module_as_both_and_drive_runs_it(
    user_dir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """One module holding a controller's and a planner's functions, named by module alone:
    each role binds its own functions (the kind the runner asks for), through the pytest
    helper as through the command."""
    monkeypatch.syspath_prepend(str(user_dir))
    result = drive("my_funcs", planner="my_funcs", map="office")
    assert_reaches_goal(result, min_clearance=0.02)
    assert result.served == {
        "controller": "my_funcs (delegates)",
        "planner": "my_funcs (delegates)",
    }
    assert "[WARNING]" not in result.host_log, result.host_log


def test_a_module_without_the_roles_function_is_refused_naming_it(user_dir: Path) -> None:
    (user_dir / "only_steer.py").write_text(
        "def compute_velocity_commands(costmap, pose, twist):\n    raise NotImplementedError\n"
    )
    result = bash("nav2-pyif sim --planner only_steer --no-progress --timeout 5", user_dir)
    assert result.returncode == 2, result.stdout + result.stderr
    assert "module 'only_steer' defines no function create_plan" in result.stderr


def test_a_misspelt_module_is_refused_before_a_host_starts(user_dir: Path) -> None:
    done = bash("nav2-pyif sim --controller my_func --no-progress", user_dir)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "unknown planner 'my_func'" in done.stderr
