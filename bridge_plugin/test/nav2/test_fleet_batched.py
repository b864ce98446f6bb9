"""Two robots, one batched planner host, in the real Nav2: two Nav2 stacks (controller_server,
planner_server, lifecycle manager and a simulated robot each), each in a ROS domain of its own
as two robots are, with their plugins on keys nav2_pyif/robot1/... and nav2_pyif/robot2/...
dialling one `planner-host --batch`. Their controllers are the JAX MPPI: the host gathers the
two robots' control cycles into one `compute_velocity_commands_batch` call (one jit-compiled
rollout kernel for both). The robots drive to different goals at the same time, so a reply
given to the wrong robot would send it the wrong way.

Needs what test_nav2_pyif.py needs, and JAX in the planner host's environment.
"""

from __future__ import annotations

import math
import os
import random
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

ROBOTS = ("robot1", "robot2")
# Each robot's goal, from the origin, on the free side of the sim's wall (x = 1 m): one north,
# one south-west, so each reaches its own only with its own commands.
GOALS = {"robot1": (0.0, 1.8), "robot2": (-1.5, -1.0)}
MPPI = "nav2_pyif_planners.mppi_jax:MPPIJax"
ASTAR = "nav2_pyif_planners.astar:AStar"
WINDOW_MS = 12.5  # a quarter of controller_server's 50 ms period


def _robot_params(text: str, robot: str) -> str:
    """The launch test's params with the plugins on this robot's keys, and the MPPI's
    ``fleet_size``: the batch shapes it compiles in configure, not in a control cycle."""
    text = text.replace(f"{nav2_testing.PREFIX}/", f"nav2_pyif/{robot}/")
    assert f"nav2_pyif/{robot}/FollowPath" in text and "desired_linear_vel: 0.5" in text
    return text.replace("desired_linear_vel: 0.5", f"fleet_size: {len(ROBOTS)}")


@pytest.fixture(scope="module")
def fleet(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    absent = nav2_testing.missing()
    if absent:
        pytest.skip("the Nav2 launch test needs: " + ", ".join(absent))
    import rclpy

    logs = tmp_path_factory.mktemp("nav2_fleet_batched")
    endpoint = f"tcp/127.0.0.1:{nav2_testing.free_port()}"
    domains = random.sample(range(100, 200), len(ROBOTS))
    stacks: dict[str, dict[str, Any]] = {}
    try:
        for robot, domain in zip(ROBOTS, domains, strict=True):
            robot_logs = logs / robot
            robot_logs.mkdir()
            _, params, procs = nav2_testing.prepare(robot_logs, endpoint)
            params.write_text(_robot_params(params.read_text(), robot))
            procs.env["ROS_DOMAIN_ID"] = str(domain)
            stacks[robot] = {"procs": procs, "params": params, "domain": domain}
        os.environ.pop("ROS_DOMAIN_ID", None)  # prepare() set it; each stack has its own

        host = stacks["robot1"]["procs"]
        serve = [
            arg
            for robot in ROBOTS
            for arg in (
                *("--serve", f"nav2_pyif/{robot}/FollowPath={MPPI}"),
                *("--serve", f"nav2_pyif/{robot}/GridBased={ASTAR}"),
            )
        ]
        command = [*(nav2_testing.host_command() or []), "--listen", endpoint]
        host.start("planner_host", [*command, "--batch", "--batch-window", str(WINDOW_MS), *serve])
        for robot, stack in stacks.items():
            stack["procs"].start("sim_robot", ["python3", str(nav2_testing.HERE / "sim_robot.py")])
            nav2_testing.start_nav2(stack["procs"], stack["params"])
            context = rclpy.Context()
            rclpy.init(context=context, domain_id=stack["domain"])
            stack["context"] = context
            stack["client"] = nav2_testing.Nav2Client(context, f"nav2_pyif_launch_test_{robot}")
        yield {"stacks": stacks, "host": host, "endpoint": endpoint}
    finally:
        for stack in stacks.values():
            if "client" in stack:
                stack["client"].destroy_node()
            if "context" in stack:
                rclpy.try_shutdown(context=stack["context"])
            stack["procs"].stop_all()


def _logs(fleet: dict[str, Any], robot: str) -> str:
    procs = fleet["stacks"][robot]["procs"]
    own = "\n".join(procs.log(n) for n in ("controller_server", "planner_server", "sim_robot"))
    return own + "\n" + fleet["host"].log("planner_host", 80)


def _drive_together(
    fleet: dict[str, Any], goals: dict[str, tuple[float, float]], controller: str
) -> dict[str, Any]:
    """Each robot planned to its goal and driven there by ``controller``, both at once; what
    the host says of that controller's batch group afterwards."""
    clients = {robot: stack["client"] for robot, stack in fleet["stacks"].items()}
    paths = {}
    for robot, client in clients.items():
        planned = client.plan(*goals[robot])
        assert planned is not None and planned.status == nav2_testing.SUCCEEDED, _logs(fleet, robot)
        paths[robot] = planned.result.path
    # Both FollowPath goals sent at once: controller_server's loop keeps the phase its goal
    # started with, so two robots started together send their cycles together, and the host
    # can batch them (robots out of phase by more than the window are served one by one).
    sent = {r: clients[r].send_follow(path, controller=controller) for r, path in paths.items()}
    futures = {}
    for robot, future in sent.items():
        handle = clients[robot].wait(future, 10.0)
        assert handle is not None and handle.accepted, f"{robot}: FollowPath not accepted"
        futures[robot] = handle.get_result_async()
    pending = set(futures)  # spin each robot's node in turn until both results are in
    for _ in range(3000):  # 0.05 s each at most: 150 s
        for robot in list(pending):
            clients[robot].spin_until(futures[robot].done, 0.025)
            if futures[robot].done():
                pending.discard(robot)
        if not pending:
            break
    for robot, future in futures.items():
        result = future.result() if future.done() else None
        assert result is not None and result.status == nav2_testing.SUCCEEDED, (
            f"{robot} with {controller}: {result}\n" + _logs(fleet, robot)
        )
        x, y = clients[robot].pose
        goal = goals[robot]
        assert math.hypot(x - goal[0], y - goal[1]) < 0.35, f"{robot} at {(x, y)}, goal {goal}"
    keys = nav2_testing.host_keys(fleet["endpoint"])
    batch: dict[str, Any] | None = keys[f"nav2_pyif/{ROBOTS[0]}/{controller}"].get("batch")
    members = [f"nav2_pyif/{robot}/{controller}" for robot in ROBOTS]
    assert batch is not None and sorted(batch["keys"]) == members, keys
    print(f"one batched host, two robots, {controller}: {batch}")
    return batch


def test_two_robots_reach_their_own_goals_with_one_batched_jax_mppi(
    fleet: dict[str, Any],
) -> None:
    for robot, stack in fleet["stacks"].items():
        states = stack["client"].wait_active(nav2_testing.SERVERS, 120.0)
        assert all(s == "active" for s in states.values()), f"{states}\n" + _logs(fleet, robot)
    batch = _drive_together(fleet, GOALS, "FollowPath")
    # Their cycles were batched: each batch of both robots serves one cycle more than it
    # makes calls (a lone robot's cycle is a batch of one). At least 2.5 s of driving
    # together, of the 7 s or so they share.
    assert batch["dropped"] == 0, batch
    assert batch["cycles"] - batch["batches"] > 50, batch
    log = fleet["host"].log("planner_host", 400)
    assert f"serving {MPPI}" in log, log
