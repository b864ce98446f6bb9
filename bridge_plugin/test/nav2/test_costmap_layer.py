"""A Python costmap layer in the real Nav2: the Python keep-out layer (KeepOutLayer) as a
plugin (PyCostmapLayer) of the global and the local costmap, one planner host serving both:

1. its polygon's cells are lethal in the published local costmap, and the plan and the robot
   go around it;
2. `ros2 param set` of the polygons takes them out of the published costmap;
3. the host killed (SIGKILL): the costmap is no longer current and FollowPath fails cleanly;
   a new host brings the layer back.
"""

from __future__ import annotations

import math
import signal
import time
from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest

PREFIX = nav2_testing.PREFIX
GOAL = (0.0, -2.0)
BAR = ((-0.8, -1.2), (0.6, -1.2), (0.6, -0.8), (-0.8, -0.8))  # across the straight way
POLYGONS = "[[" + ", ".join(f"[{x}, {y}]" for x, y in BAR) + "]]"
PLANNERS = (
    *nav2_testing.REFERENCE_PLANNERS,
    *("--serve", f"{PREFIX}/keepout=nav2_pyif_planners.keepout_layer:KeepOutLayer"),
)
SUCCEEDED, ABORTED = nav2_testing.SUCCEEDED, nav2_testing.ABORTED


def with_keepout_layers(text: str) -> str:
    """Both costmaps get the Python keep-out layer before their inflation layer."""
    lines = text.splitlines()
    follow = lines.index(f'      key: "{PREFIX}/FollowPath"')
    connect = lines[follow + 1].strip()
    layer = f"""      keepout:
        plugin: "nav2_pyif_bridge::PyCostmapLayer"
        key: "{PREFIX}/keepout"
        {connect}
        timeout: 0.5
        wait_for_host: 20.0
        polygons: "{POLYGONS}\""""
    out = text.replace(
        'plugins: ["obstacle_layer", "inflation_layer"]',
        f'plugins: ["obstacle_layer", "keepout", "inflation_layer"]\n{layer}',
    )
    # a robot standing still gets only costmap_updates otherwise: the test reads whole grids
    out = out.replace(
        "rolling_window: true", "rolling_window: true\n      always_send_full_costmap: true"
    )
    return out.replace(
        'plugins: ["static_layer", "inflation_layer"]',
        f'plugins: ["static_layer", "keepout", "inflation_layer"]\n{layer}',
    )


@pytest.fixture(scope="module")
def nav2(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    yield from nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_costmap_layer"),
        planners=PLANNERS,
        edit_params=with_keepout_layers,
    )


def in_bar(x: float, y: float, margin: float = 0.0) -> bool:
    return -0.8 - margin <= x <= 0.6 + margin and -1.2 - margin <= y <= -0.8 + margin


def lethal_cells(grid: Any) -> list[tuple[float, float]]:
    """World centres of the OccupancyGrid's lethal (100) cells."""
    info = grid.info
    return [
        (
            info.origin.position.x + (i % info.width + 0.5) * info.resolution,
            info.origin.position.y + (i // info.width + 0.5) * info.resolution,
        )
        for i, value in enumerate(grid.data)
        if value == 100
    ]


def test_python_keepout_layer_in_nav2s_costmaps(nav2: dict[str, Any]) -> None:
    from nav_msgs.msg import OccupancyGrid
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

    client, procs = nav2["client"], nav2["procs"]
    servers = nav2_testing.SERVERS
    states = client.wait_active(servers, 90.0)
    assert all(s == "active" for s in states.values()), f"{states}\n" + "\n".join(
        procs.log(n) for n in (*servers, "lifecycle_manager", "planner_host")
    )
    latest: dict[str, Any] = {}
    qos = QoSProfile(
        depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL, reliability=ReliabilityPolicy.RELIABLE
    )
    client.create_subscription(
        OccupancyGrid, "local_costmap/costmap", lambda m: latest.update(grid=m), qos
    )

    def lethal_now(timeout: float = 10.0) -> list[tuple[float, float]]:
        latest.clear()  # the next published costmap
        assert client.spin_until(lambda: "grid" in latest, timeout), procs.log("controller_server")
        return lethal_cells(latest["grid"])

    # 1. the bar's cells are lethal in the published local costmap, and nothing else is
    cells = lethal_now()
    assert len(cells) > 100, f"{len(cells)} lethal cells\n" + procs.log("controller_server")
    assert all(in_bar(x, y, 0.05) for x, y in cells), [c for c in cells if not in_bar(*c, 0.05)]
    # the plan and the robot go around it
    planned = client.plan(*GOAL)
    assert planned is not None and planned.status == SUCCEEDED, procs.log("planner_server")
    path = planned.result.path
    assert not any(in_bar(p.pose.position.x, p.pose.position.y) for p in path.poses)
    handle = client.follow(path)
    track: list[tuple[float, float]] = []
    result_future = handle.get_result_async()

    def driven() -> bool:  # the robot's pose at every spin, until the goal's result
        if client.pose is not None:
            track.append(client.pose)
        return bool(result_future.done())

    client.spin_until(driven, 90.0)
    result = result_future.result() if result_future.done() else None
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    assert track and not any(in_bar(x, y) for x, y in track), "the robot drove through the bar"
    x, y = client.pose
    assert math.hypot(x - GOAL[0], y - GOAL[1]) < 0.35, f"robot at {(x, y)}"

    # 2. `ros2 param set` of the polygons: their cells leave the published costmap
    node = "local_costmap/local_costmap"
    assert client.set_parameter(node, "keepout.polygons", "[]") == (True, "")
    deadline = time.monotonic() + 15.0
    while lethal_now() and time.monotonic() < deadline:
        pass
    assert not lethal_now(), "the keep-out cells stayed after their polygons were removed"
    assert client.set_parameter(node, "keepout.polygons", POLYGONS) == (True, "")
    assert client.spin_until(lambda: len(lethal_now()) > 100, 15.0)

    # 3. the host dies: the costmap is not current, FollowPath does not drive, Nav2 stays up
    killed = time.time()
    procs.kill("planner_host", signal.SIGKILL)
    client.spin_until(lambda: False, 2.0)
    handle = client.follow(path)
    if nav2_testing.costmap_wait_bounded():  # Jazzy on: aborted at costmap_update_timeout
        result = client.wait(handle.get_result_async(), 30.0)
        logs = procs.log("controller_server")
        assert result is not None and result.status == ABORTED, f"FollowPath: {result}\n{logs}"
    else:  # Humble waits for a current costmap without end: the robot is held until then
        held_at = client.pose
        result_future = handle.get_result_async()
        client.spin_until(result_future.done, 5.0)
        logs = procs.log("controller_server")
        assert not result_future.done(), f"FollowPath ended on a stale costmap: {logs}"
        assert held_at is not None and client.pose is not None
        moved = math.hypot(client.pose[0] - held_at[0], client.pose[1] - held_at[1])
        assert moved < 0.02, f"the robot drove {moved:.2f} m on a costmap that is not current"
        # Humble's wait loop does not look at a cancel either (one sent here was not
        # honoured): the goal, where the robot already is, ends once the costmap is current
        nav2["start_host"]()
        result = client.wait(result_future, 60.0)
        logs = procs.log("controller_server")
        assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    assert procs.logged_at("controller_server", "the costmap is not current", killed), logs
    assert client.wait_active(servers, 10.0) == dict.fromkeys(servers, "active")
    # a new host (Humble's was started above): the layer answers again, the next goal succeeds
    if nav2_testing.costmap_wait_bounded():
        nav2["start_host"]()
    deadline = time.monotonic() + 60.0
    result = None
    while time.monotonic() < deadline:
        planned = client.plan(0.0, 0.0)
        if planned is not None and planned.status == SUCCEEDED:
            result = client.wait(client.follow(planned.result.path).get_result_async(), 90.0)
            if result is not None and result.status == SUCCEEDED:
                break
        client.spin_until(lambda: False, 1.0)
    logs = "\n".join(procs.log(n) for n in ("controller_server", "planner_host"))
    assert result is not None and result.status == SUCCEEDED, f"FollowPath: {result}\n{logs}"
    assert len(lethal_now()) > 100
