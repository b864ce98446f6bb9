"""Inputs and debug outputs through a real host: messages (real rclpy messages, serialized as
the plugin's generic subscription delivers them) reach ``self.inputs`` in their NumPy forms and
persist between calls; debug outputs come back only when wanted, as real messages."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
from geometry_msgs.msg import Twist
from nav2_pyif._ros_types import RMW_CHECKED, MessageTypeError, message_class, serialize
from nav2_pyif.exceptions import ControllerException
from nav2_pyif.inputs import from_cdr
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Image, LaserScan, PointCloud2, PointField

from tests.test_host_e2e import controller, pose

pytestmark = pytest.mark.integration

KEY = "nav2_pyif/test_robot/FollowPath"


def laser_scan(beams: int = 720, nearest: float = 0.75) -> Any:
    msg = LaserScan()
    msg.header.frame_id = "base_scan"
    msg.angle_min, msg.angle_max = -math.pi, math.pi
    msg.angle_increment = 2 * math.pi / beams
    msg.range_min, msg.range_max = 0.05, 12.0
    ranges = np.full(beams, 3.0, dtype=np.float32)
    ranges[beams // 3] = nearest
    ranges[0] = np.inf
    msg.ranges = ranges.tolist()
    return msg


def image(height: int = 3, width: int = 4) -> Any:
    msg = Image(height=height, width=width, encoding="rgb8", step=width * 3 + 2)  # padded rows
    rows = np.zeros((height, width * 3 + 2), dtype=np.uint8)
    rows[:, : width * 3] = np.arange(height * width * 3, dtype=np.uint8).reshape(height, -1)
    rows[:, width * 3 :] = 99  # padding must not show in the pixels
    msg.data = rows.tobytes()
    return msg


def cloud(n: int = 100) -> Any:
    fields = [
        PointField(name=axis, offset=4 * i, datatype=PointField.FLOAT32, count=1)
        for i, axis in enumerate("xyz")
    ] + [PointField(name="intensity", offset=12, datatype=PointField.UINT16, count=1)]
    dtype = np.dtype(
        {
            "names": ["x", "y", "z", "intensity"],
            "formats": ["<f4", "<f4", "<f4", "<u2"],
            "offsets": [0, 4, 8, 12],
            "itemsize": 16,
        }
    )
    points = np.zeros(n, dtype=dtype)
    points["x"] = np.arange(n, dtype=np.float32) * 0.5
    points["intensity"] = 7
    msg = PointCloud2(height=1, width=n, fields=fields, point_step=16, row_step=16 * n)
    msg.is_dense = True
    msg.data = points.tobytes()
    return msg


def odometry() -> Any:
    msg = Odometry()
    msg.header.frame_id, msg.child_frame_id = "odom", "base_link"
    msg.pose.pose.position.x = 4.25
    msg.pose.pose.orientation.w = 1.0
    msg.twist.twist.linear.x = 0.3
    return msg


def test_array_forms_of_real_messages() -> None:
    scan = from_cdr("sensor_msgs/msg/LaserScan", serialize(laser_scan(720, 0.75)))
    assert scan.ranges.dtype == np.float32 and scan.ranges.shape == (720,)
    assert scan.ranges[240] == np.float32(0.75) and np.isposinf(scan.ranges[0])
    assert scan.angles[0] == np.float32(-math.pi) and scan.frame_id == "base_scan"
    img = from_cdr("sensor_msgs/msg/Image", serialize(image()))
    assert img.pixels.shape == (3, 4, 3) and img.pixels.dtype == np.uint8
    assert img.pixels[1, 0, 0] == 12 and 99 not in img.pixels
    points = from_cdr("sensor_msgs/msg/PointCloud2", serialize(cloud(100))).points
    assert points.shape == (100,) and points["x"][3] == 1.5 and (points["intensity"] == 7).all()
    odom = from_cdr("nav_msgs/msg/Odometry", serialize(odometry()))
    assert odom.pose.tolist() == [4.25, 0, 0, 0, 0, 0, 1.0] and odom.twist[0] == 0.3
    # a type without an array form: the rclpy message itself
    twist = Twist()
    twist.linear.x = 0.5
    assert from_cdr("geometry_msgs/msg/Twist", serialize(twist)) == twist
    with pytest.raises(MessageTypeError, match="not a message type name"):
        message_class("sensor_msgs/LaserScan")
    with pytest.raises(MessageTypeError, match="not available on this host"):
        message_class("no_such_msgs/msg/Thing")


def test_inputs_and_debug_outputs_through_a_host(start_host: Any, zsession_factory: Any) -> None:
    host = start_host("--key", KEY, "--planner", "sensor_planners:ScanEcho")
    client = controller(zsession_factory, host)
    client.configure()
    assert client.debug_outputs == {
        "trajectories": "visualization_msgs/msg/MarkerArray",
        "lookahead_point": "geometry_msgs/msg/PointStamped",
        "local_plan": "nav_msgs/msg/Path",
    }
    client.activate()
    cmd = client.compute_velocity_commands(pose(), Twist())
    assert (cmd.twist.linear.x, cmd.twist.linear.y) == (0.0, 0.0)  # no input yet
    assert client.debug == {}  # nobody subscribes: nothing built, nothing sent

    cmd = client.compute_velocity_commands(
        pose(),
        Twist(),
        inputs={"scan": (laser_scan(720, 0.75), 1), "camera": (image(), 2)},
        debug_wanted=["lookahead_point", "trajectories"],
    )
    lin, ang = cmd.twist.linear, cmd.twist.angular
    assert (lin.x, lin.y, lin.z) == (0.75, 2.0, 1.0)
    assert ang.x == float(np.arange(36).sum())
    assert set(client.debug) == {"lookahead_point", "trajectories"}
    point = client.debug["lookahead_point"]
    assert (point.header.frame_id, point.point.x, point.point.y) == ("odom", 2.0, 1.0)
    markers = client.debug["trajectories"].markers
    assert markers[0].action == markers[0].DELETEALL and len(markers) == 4
    assert [(p.x, p.y) for p in markers[3].points][-1] == (2.0, 3.0)

    # the next cycle sends no scan: the planner still has the latest one
    cmd = client.compute_velocity_commands(
        pose(),
        Twist(),
        inputs={"cloud": (cloud(), 3), "odom": (odometry(), 4)},
        debug_wanted=["local_plan"],
    )
    lin, ang = cmd.twist.linear, cmd.twist.angular
    assert (lin.x, lin.y, lin.z) == (0.75, 4.0, 0.0)
    assert ang.y == float(np.arange(100).sum() * 0.5) and ang.z == 4.25
    assert len(client.debug["local_plan"].poses) == 2 and set(client.debug) == {"local_plan"}


def test_undeclared_debug_output_is_a_controller_error(
    start_host: Any, zsession_factory: Any
) -> None:
    host = start_host("--key", KEY, "--planner", "sensor_planners:BadDebug")
    client = controller(zsession_factory, host)
    client.configure()
    client.activate()
    with pytest.raises(ControllerException, match="'carrot' is not declared"):
        client.compute_velocity_commands(pose(), Twist())


def test_a_host_beside_a_nav2_on_another_rmw_still_reads_its_inputs(
    monkeypatch: pytest.MonkeyPatch, start_host: Any, zsession_factory: Any
) -> None:
    """A host inherits RMW_IMPLEMENTATION=rmw_zenoh_cpp from a Nav2 on rmw_zenoh but has only
    the default rmw: rcl would end its worker (exit 102) when rclpy loads one to deserialize.
    It serializes with the default rmw instead, and says so."""
    monkeypatch.setenv("RMW_IMPLEMENTATION", "rmw_not_installed_here_cpp")
    host = start_host("--key", KEY, "--planner", "sensor_planners:ScanEcho")
    monkeypatch.delenv("RMW_IMPLEMENTATION")  # the host's only: this process serializes too
    client = controller(zsession_factory, host)
    client.configure()
    client.activate()
    cmd = client.compute_velocity_commands(
        pose(),
        Twist(),
        inputs={"scan": (laser_scan(720, 0.75), 1)},
        debug_wanted=["lookahead_point"],
    )
    assert cmd.twist.linear.x == 0.75
    assert client.debug["lookahead_point"].point.x == 2.0
    assert "RMW_IMPLEMENTATION=rmw_not_installed_here_cpp cannot be loaded" in host.log()
    assert "exited with code 102" not in host.log()


def test_warming_the_serialization_loads_it_before_any_input() -> None:
    """What a controller's configure does (nav2_pyif._ros_types.warm_serialization), in a
    fresh interpreter: rclpy's serialization is loaded after it, and was not before."""
    script = (
        "import sys\n"
        "from nav2_pyif._ros_types import warm_serialization\n"
        "assert 'rclpy.serialization' not in sys.modules\n"
        "warm_serialization()\n"
        "assert 'rclpy.serialization' in sys.modules\n"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("RMW_IMPLEMENTATION", RMW_CHECKED)}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr


def test_warming_waits_for_the_hosts_rmw_check() -> None:
    """With $RMW_IMPLEMENTATION set, a process that has not checked it (a unit test, a client)
    warms nothing and starts no probe; a worker of a host that checked it (the marker it
    inherits) warms as above."""
    script = (
        "import subprocess, sys\n"
        "def refused(*a, **k): raise AssertionError('a process was started')\n"
        "subprocess.run = subprocess.Popen = refused\n"
        "from nav2_pyif._ros_types import warm_serialization\n"
        "warm_serialization()\n"
        "print('rclpy.serialization' in sys.modules)\n"
    )
    rmw = {"RMW_IMPLEMENTATION": "rmw_fastrtps_cpp"}
    unchecked = {k: v for k, v in os.environ.items() if k != RMW_CHECKED} | rmw
    checked = unchecked | {RMW_CHECKED: "rmw_fastrtps_cpp"}
    for env, loaded in ((unchecked, "False"), (checked, "True")):
        done = subprocess.run(
            [sys.executable, "-c", script], capture_output=True, text=True, env=env
        )
        assert done.returncode == 0 and done.stdout.strip() == loaded, done.stdout + done.stderr
