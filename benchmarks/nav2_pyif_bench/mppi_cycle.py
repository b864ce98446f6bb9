"""Nav2MPPI's whole control cycle as the planner host runs it, in parts: the plan pruned
(Nav2's path handler, NumPy), the step's inputs, the compiled step's dispatch, the wait for
its reply, the TwistStamped; then the whole ``compute_velocity_commands``. Wall time and the
process's CPU time (all its threads: XLA's too) per part. A Nav2 bringup set-up: Nav2 Jazzy's
FollowPath MPPI block, a round robot, a 3 m x 3 m local costmap, a 1000-pose plan (NavFn's
spacing, 0.05 m) starting 0.5 m behind the robot, which moves at 0.3 m/s."""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

#: the parts, in the order the cycle runs them
PARTS = (
    "step inputs (pruning included)",
    "of which plan pruning",
    "step dispatch",
    "step wait + reply",
    "TwistStamped",
)

#: the whole cycle started cold (``--cold``)
COLD_ROWS = ("whole cycle, last cache flushed first", "whole cycle, one every 50 ms (20 Hz)")


def configured_robot(rollouts: int) -> tuple[Any, Any]:
    """A configured Nav2MPPI and its plan."""
    from nav2_pyif import Costmap, Inflation, Parameters, Plan
    from nav2_pyif._context import PluginContext
    from nav2_pyif_planners.mppi_nav2 import Nav2MPPI, nav2_jazzy_params

    along = 9.5 + np.arange(1000) * 0.05
    plan = Plan(np.column_stack([along, 0.2 * np.sin(along / 4), np.cos(along / 4) * 0.05]), "map")
    costmap = Costmap(
        np.zeros((60, 60), np.uint8), 0.05, origin_x=8.5, origin_y=-1.5, robot_radius=0.22,
        inflation=Inflation(0.55, 3.0),
    )  # fmt: skip
    params = Parameters({**nav2_jazzy_params(), "batch_size": rollouts, "visualize": False})
    robot = Nav2MPPI()
    robot._attach(
        PluginContext("P", "server", "map", "base_link", costmap, params, logging.getLogger("p"))
    )
    robot.configure()
    return robot, plan


def last_cache_bytes() -> int:
    """The largest CPU cache this machine reports (sysfs), 64 MiB where it reports none."""
    units = {"K": 1 << 10, "M": 1 << 20, "G": 1 << 30}
    sizes = [
        int(text[:-1]) * units[text[-1]] if text[-1] in units else int(text)
        for text in (
            f.read_text().strip()
            for f in Path("/sys/devices/system/cpu/cpu0/cache").glob("index*/size")
        )
        if text
    ]
    return max(sizes, default=64 << 20)


def cycle(rollouts: int, repeat: int, cold: bool = False) -> dict[str, Any]:
    from geometry_msgs.msg import Twist
    from nav2_pyif.runner.run import pose_msg

    robot, plan = configured_robot(rollouts)
    pose = pose_msg(10.0, 0.2 * np.sin(2.5), 0.0)
    state = np.array([10.0, 0.2 * np.sin(2.5), 0.0])
    velocity = Twist()
    velocity.linear.x = 0.3
    rows = (*PARTS, "whole cycle", *(COLD_ROWS if cold else ()))
    wall: dict[str, list[float]] = {name: [] for name in rows}
    cpu: dict[str, list[float]] = {name: [] for name in wall}

    def timed(name: str, fn: Callable[..., Any], *args: Any) -> Any:
        w, c = time.perf_counter(), time.process_time()
        out = fn(*args)
        wall[name].append(time.perf_counter() - w)
        cpu[name].append(time.process_time() - c)
        return out

    for n in range(repeat + 10):
        robot.set_plan(plan)  # a plan per cycle: every cycle prunes the same 1000 poses
        if n == 10:
            for values in (*wall.values(), *cpu.values()):
                values.clear()
        inputs = timed(PARTS[0], robot.cycle_inputs, state, velocity, None)
        out = timed("step dispatch", robot._run, inputs)
        command = timed("step wait + reply", np.asarray, out.reply)[:3]
        timed("TwistStamped", robot.twist, pose, command)
        robot.set_plan(plan)
        timed(PARTS[1], robot.path.transform, *state[:2], robot.costmap)
        robot.set_plan(plan)
        timed("whole cycle", robot.compute_velocity_commands, pose, velocity, None)
    if cold:
        from nav2_pyif_bench.protocol_bench import paced

        def cold_call(name: str, first: Callable[[], Any]) -> int:
            robot.set_plan(plan)
            first()
            timed(name, robot.compute_velocity_commands, pose, velocity, None)
            return 0

        # a read past the last cache evicts the cycle's code and data, as other work does
        # between two of Nav2's calls; then the calls as Nav2 makes them, 50 ms apart
        flushing = np.ones(int(1.1 * last_cache_bytes()) // 8)
        for _ in range(repeat):
            cold_call(COLD_ROWS[0], flushing.sum)
        paced({COLD_ROWS[1]: lambda: cold_call(COLD_ROWS[1], lambda: None)}, repeat, 20.0)
    return {
        name: {
            "wall_median_ms": float(np.median(wall[name]) * 1e3),
            "wall_p99_ms": float(np.percentile(wall[name], 99) * 1e3),
            "cpu_median_ms": float(np.median(cpu[name]) * 1e3),
        }
        for name in wall
    }
