"""The common workaround: a separate rclpy node answering over topics.

Subscribes nav_msgs/Odometry (pose + velocity) on /pyif_bench/odom and answers a
geometry_msgs/TwistStamped on /pyif_bench/cmd_vel; subscribes nav_msgs/Path on
/pyif_bench/plan, converts it to an (N, 3) NumPy array and acknowledges on /pyif_bench/plan_ack.
"""

from __future__ import annotations

import math

import numpy as np
import rclpy
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry, Path
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import Header

QOS = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)


class PlannerNode(Node):
    def __init__(self) -> None:
        super().__init__("pyif_bench_planner")
        self.cmd_pub = self.create_publisher(TwistStamped, "/pyif_bench/cmd_vel", QOS)
        self.ack_pub = self.create_publisher(Header, "/pyif_bench/plan_ack", QOS)
        self.create_subscription(Odometry, "/pyif_bench/odom", self.on_odom, QOS)
        self.create_subscription(Path, "/pyif_bench/plan", self.on_plan, QOS)

    def on_odom(self, odom: Odometry) -> None:
        cmd = TwistStamped(header=odom.header)
        cmd.twist.linear.x = 0.1
        self.cmd_pub.publish(cmd)

    def on_plan(self, path: Path) -> None:
        xy_yaw = np.array(
            [
                (
                    p.pose.position.x,
                    p.pose.position.y,
                    2.0 * math.atan2(p.pose.orientation.z, p.pose.orientation.w),
                )
                for p in path.poses
            ]
        ).reshape(-1, 3)
        self.ack_pub.publish(Header(frame_id=str(xy_yaw.shape[0]), stamp=path.header.stamp))


def main() -> None:
    rclpy.init()
    serve(PlannerNode())


def serve(node: Node) -> None:
    """Spin ``node`` until SIGINT/SIGTERM, then shut rclpy down (rclpy.init() done)."""
    print("ready", flush=True)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()  # type: ignore[attr-defined]


if __name__ == "__main__":
    main()
