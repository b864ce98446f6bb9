"""Two robots, one batched planner host, in the real Nav2: two Nav2 stacks (controller_server,
planner_server, lifecycle manager and a simulated robot with a laser each), each in a ROS
domain of its own as two robots are, with their plugins on keys nav2_pyif/robot1/... and
nav2_pyif/robot2/... dialling one `planner-host --batch`. Each controller_server has two
Python controllers: the learned controller (Learned: one forward pass for both robots, each
from its own scan) and the JAX MPPI (FollowPath: one jit-compiled rollout kernel for both).
The host gathers the two robots' control cycles into one `compute_velocity_commands_batch`
call. The robots drive to different goals at the same time, so a reply given to the wrong
robot would send it the wrong way.

The learned controller's policy is trained first, in the planner host's environment
(``nav2_pyif_planners.learned.pipeline``): MPPI demonstrations in the offline runner on the
simulated robot's own world (its wall, drawn into a map larger than the Nav2 one so that no
map edge comes within the policy's scan range) with its laser (181 beams over the front half,
4 m). A policy trained on other maps alone sees an open room as nothing it has learned.

Needs what test_nav2_pyif.py needs, and JAX in the planner host's environment.
"""

from __future__ import annotations

import json
import math
import random
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import nav2_testing
import pytest
import sim_robot

ROBOTS = ("robot1", "robot2")
# First the learned controller, from the origin (facing -x, away from the sim's wall) to a
# goal ahead on the left or the right; then the MPPI from there to a goal on the other side,
# so each robot reaches its own only with its own commands.
START_YAW = math.pi
LEARNED_GOALS = {"robot1": (-2.0, 0.6), "robot2": (-2.0, -0.6)}
MPPI_GOALS = {"robot1": (0.0, 2.0), "robot2": (0.0, -2.0)}
MPPI = "nav2_pyif_planners.mppi_jax:MPPIJax"
LEARNED = "nav2_pyif_planners.learned.controller:LearnedController"
ASTAR = "nav2_pyif_planners.astar:AStar"
WINDOW_MS = 12.5  # a quarter of controller_server's 50 ms period


# Demonstrations on the sim's world (argv: the map YAML, the weights, the routes as JSON).
TRAIN = """
import json, math, sys
from pathlib import Path
from nav2_pyif.runner.laser import LaserSpec
from nav2_pyif_planners.learned.pipeline import LearnConfig, Task, learn
routes = [Task(sys.argv[1], tuple(a), tuple(b)) for a, b in json.loads(sys.argv[3])]
laser = LaserSpec(beams=181, angle_min=-math.pi / 2, angle_max=math.pi / 2, range_max=4.0)
config = LearnConfig(tasks=routes, runs=2, steps=1500, weights=Path(sys.argv[2]),
                     evaluate=None, laser=laser, timeout=40.0)
print(learn(config).training)
"""
TRAIN_MAP_M = 16.0  # the sim's 8 m world, its wall at the same place, in a larger map


def _sim_world(directory: Path) -> Path:
    """The simulated robot's world as a runner map (PGM and YAML): free, but for its wall."""
    cells = round(TRAIN_MAP_M / sim_robot.RESOLUTION)
    half = TRAIN_MAP_M / 2
    image = bytearray([254]) * (cells * cells)  # free
    mx = int((sim_robot.WALL_X + half) / sim_robot.RESOLUTION)
    low, high = (int((y + half) / sim_robot.RESOLUTION) for y in sim_robot.WALL_Y)
    for my in range(low, high):
        for dx in range(2):
            image[(cells - 1 - my) * cells + mx + dx] = 0  # PGM rows run from the top
    (directory / "sim_world.pgm").write_bytes(b"P5\n%d %d\n255\n" % (cells, cells) + image)
    yaml = directory / "sim_world.yaml"
    yaml.write_text(
        "image: sim_world.pgm\nmode: trinary\n"
        f"resolution: {sim_robot.RESOLUTION}\norigin: [{-half}, {-half}, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return yaml


@pytest.fixture(scope="module")
def weights(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The learned controller's policy, trained in the planner host's environment."""
    python = nav2_testing.project_command("python")
    if python is None:
        pytest.skip("the learned controller's training needs $NAV2_PYIF_RUN (the host's env)")
    directory = tmp_path_factory.mktemp("policy")
    routes = [((0.0, 0.0, START_YAW), (*goal, START_YAW)) for goal in LEARNED_GOALS.values()]
    routes += [((0.0, 0.0, START_YAW), (-2.5, 0.0, START_YAW))]
    path = directory / "policy.npz"
    command = [*python, "-c", TRAIN, str(_sim_world(directory)), str(path), json.dumps(routes)]
    trained = subprocess.run(command, capture_output=True, text=True, timeout=1200)
    assert trained.returncode == 0 and path.is_file(), trained.stdout + trained.stderr[-3000:]
    return path


def _robot_params(text: str, robot: str, weights: Path) -> str:
    """The launch test's params with the plugins on this robot's keys; the MPPI's and the
    policy's ``fleet_size`` (the batch shapes they compile in configure, not in a control
    cycle); the learned controller beside the MPPI, with the robot's scan as its input."""
    text = text.replace(f"{nav2_testing.PREFIX}/", f"nav2_pyif/{robot}/")
    fleet_size = f"fleet_size: {len(ROBOTS)}"
    anchor = '    controller_plugins: ["FollowPath"]\n'
    assert anchor in text and "desired_linear_vel: 0.5" in text
    # where FollowPath meets the host (zenoh_connect, or zenoh_config on zenoh-c): the same
    lines = text.splitlines()
    after_key = lines[lines.index(f'      key: "nav2_pyif/{robot}/FollowPath"') + 1]
    assert after_key.startswith("      zenoh_"), after_key
    learned = f"""    Learned:
      plugin: "nav2_pyif_bridge::PyController"
      key: "nav2_pyif/{robot}/Learned"
{after_key}
      timeout: 0.5
      wait_for_host: 20.0
      weights: "{weights}"
      {fleet_size}
      inputs: ["scan"]
      scan:
        topic: /scan
        type: sensor_msgs/msg/LaserScan
"""
    text = text.replace(anchor, '    controller_plugins: ["FollowPath", "Learned"]\n')
    text = text.replace("    FollowPath:\n", learned + "    FollowPath:\n")
    return text.replace("desired_linear_vel: 0.5", fleet_size)


@pytest.fixture(scope="module")
def fleet(tmp_path_factory: pytest.TempPathFactory, weights: Path) -> Iterator[dict[str, Any]]:
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
            _, params, procs = nav2_testing.prepare(robot_logs, endpoint, domain)
            params.write_text(_robot_params(params.read_text(), robot, weights))
            stacks[robot] = {"procs": procs, "params": params, "domain": domain}

        host = stacks["robot1"]["procs"]
        serve = [
            arg
            for robot in ROBOTS
            for arg in (
                *("--serve", f"nav2_pyif/{robot}/FollowPath={MPPI}"),
                *("--serve", f"nav2_pyif/{robot}/Learned={LEARNED}"),
                *("--serve", f"nav2_pyif/{robot}/GridBased={ASTAR}"),
            )
        ]
        command = [*(nav2_testing.host_command() or []), "--listen", endpoint]
        host.start("planner_host", [*command, "--batch", "--batch-window", str(WINDOW_MS), *serve])
        for robot, stack in stacks.items():
            simulated = [str(nav2_testing.HERE / "sim_robot.py"), "--scan", "--yaw", str(START_YAW)]
            stack["procs"].start("sim_robot", ["python3", *simulated])
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
    took: dict[str, float] = {}
    began = time.monotonic()
    pending = set(futures)  # spin each robot's node in turn until both results are in
    for _ in range(3000):  # 0.05 s each at most: 150 s
        for robot in list(pending):
            clients[robot].spin_until(futures[robot].done, 0.025)
            if futures[robot].done():
                pending.discard(robot)
                took[robot] = time.monotonic() - began
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
    print(f"one batched host, two robots, {controller}: {batch}, drives {took}")
    # Every cycle of both robots went through the batch group: controller_server's 20 Hz for
    # as long as each drove (half of it, for loop overruns on a loaded machine).
    assert batch["dropped"] == 0, batch
    assert batch["cycles"] >= 0.5 * 20 * sum(took.values()), (batch, took)
    return batch


# Whether the two robots' cycles also share calls depends on their phases: controller_server
# runs its loop at the phase its goal started with, and both goals are sent at once. Mostly
# they shared nearly every call (285 cycles in about 145 calls, 405 in about 210); in one run
# of four on Humble the two loops ran out of phase by more than the window and few were
# shared. tests/test_batched.py asserts the gathering itself, with clients in phase; this test
# asserts that every cycle of both robots went through the batch group.


def test_two_robots_reach_their_own_goals_with_one_batched_learned_controller(
    fleet: dict[str, Any],
) -> None:
    for robot, stack in fleet["stacks"].items():
        states = stack["client"].wait_active(nav2_testing.SERVERS, 120.0)
        assert all(s == "active" for s in states.values()), f"{states}\n" + _logs(fleet, robot)
    _drive_together(fleet, LEARNED_GOALS, "Learned")
    log = fleet["host"].log("planner_host", 400)
    assert f"serving {LEARNED}" in log, log


def test_two_robots_reach_their_own_goals_with_one_batched_jax_mppi(
    fleet: dict[str, Any],
) -> None:
    _drive_together(fleet, MPPI_GOALS, "FollowPath")
    log = fleet["host"].log("planner_host", 400)
    assert f"serving {MPPI}" in log, log
