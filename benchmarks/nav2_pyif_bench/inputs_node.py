"""The rclpy-topic side of ``nav2-pyif-bench inputs``: a node that subscribes to a scan, a
cloud and an image, turns each into its NumPy form as the planner host does
(``nav2_pyif.inputs.ARRAY_FORMS``) and acknowledges it on /pyif_bench/input_ack."""

from __future__ import annotations

from typing import Any

import rclpy
from nav2_pyif.inputs import ARRAY_FORMS
from rclpy.node import Node
from sensor_msgs.msg import Image, LaserScan, PointCloud2
from std_msgs.msg import Header

from nav2_pyif_bench.rclpy_node import QOS, serve

#: input name -> (message class, ROS type name); topic /pyif_bench/<name>
TOPICS: dict[str, tuple[Any, str]] = {
    "scan": (LaserScan, "sensor_msgs/msg/LaserScan"),
    "cloud": (PointCloud2, "sensor_msgs/msg/PointCloud2"),
    "image": (Image, "sensor_msgs/msg/Image"),
}


class InputsNode(Node):
    def __init__(self) -> None:
        super().__init__("pyif_bench_inputs")
        self.ack = self.create_publisher(Header, "/pyif_bench/input_ack", QOS)
        for name, (cls, type_name) in TOPICS.items():
            self.create_subscription(cls, f"/pyif_bench/{name}", self._callback(type_name), QOS)

    def _callback(self, type_name: str) -> Any:
        form = ARRAY_FORMS[type_name]

        def on_input(msg: Any) -> None:
            form(msg)
            self.ack.publish(msg.header)

        return on_input


def main() -> None:
    rclpy.init()
    serve(InputsNode())


if __name__ == "__main__":
    main()
