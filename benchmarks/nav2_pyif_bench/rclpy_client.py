"""The bench's side of the rclpy-node workaround: publish, then wait for the answer."""

from __future__ import annotations

import threading
import time
from typing import Any

import rclpy
from geometry_msgs.msg import PoseStamped, TwistStamped
from nav_msgs.msg import Odometry, Path
from rclpy.executors import SingleThreadedExecutor
from std_msgs.msg import Header

from nav2_pyif_bench.rclpy_node import QOS


class RclpyWorkaroundClient:
    def __init__(self) -> None:
        rclpy.init()
        self.node = rclpy.create_node("pyif_bench_client")
        self.odom_pub = self.node.create_publisher(Odometry, "/pyif_bench/odom", QOS)
        self.plan_pub = self.node.create_publisher(Path, "/pyif_bench/plan", QOS)
        self._cmd = threading.Event()
        self._ack = threading.Event()
        self.node.create_subscription(
            TwistStamped, "/pyif_bench/cmd_vel", lambda _m: self._cmd.set(), QOS
        )
        self.node.create_subscription(
            Header, "/pyif_bench/plan_ack", lambda _m: self._ack.set(), QOS
        )
        # Spun by the measuring thread itself (publish, then spin until the answer): no
        # background executor thread competing for the GIL while Zenoh rounds are measured.
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)

    def wait_ready(self, timeout: float = 30.0) -> bool:
        """Both directions matched and one full exchange done (DDS discovery is slow)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.odom_pub.get_subscription_count() and self.plan_pub.get_subscription_count():
                try:
                    self.cycle(Odometry(), timeout=0.5)
                    return True
                except TimeoutError:
                    pass
            self.executor.spin_once(timeout_sec=0.05)
        return False

    def _spin_until(self, event: threading.Event, deadline: float, what: str) -> None:
        while not event.is_set():
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError(what)
            self.executor.spin_once(timeout_sec=remaining)

    def cycle(self, odom: Any, timeout: float = 1.0) -> int:
        self._cmd.clear()
        start = time.perf_counter_ns()
        self.odom_pub.publish(odom)
        self._spin_until(self._cmd, time.monotonic() + timeout, "rclpy node did not answer")
        return time.perf_counter_ns() - start

    def send_plan(self, path: Any, timeout: float = 5.0) -> int:
        self._ack.clear()
        start = time.perf_counter_ns()
        self.plan_pub.publish(path)
        self._spin_until(
            self._ack, time.monotonic() + timeout, "rclpy node did not acknowledge the plan"
        )
        return time.perf_counter_ns() - start

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        rclpy.try_shutdown()  # type: ignore[attr-defined]


def path_message(n: int) -> Any:
    path = Path()
    path.header.frame_id = "odom"
    poses = []
    for i in range(n):
        p = PoseStamped()
        p.header.frame_id = "odom"
        p.pose.position.x = i * 0.05
        p.pose.orientation.w = 1.0
        poses.append(p)
    path.poses = poses
    return path
