"""Inputs' cost: a 720-beam LaserScan at 20 Hz, a 30 000-point PointCloud2 at 10 Hz
and a 640 x 480 rgb8 Image at 10 Hz, a new one with every control cycle, through the protocol
to a planner host whose controller gets it as NumPy (``self.inputs``), beside the same message
published on a ROS topic to an rclpy node that converts it alike and acknowledges it.

Both sides start from the serialized (CDR) message, as each gets it in Nav2: the C++ plugin's
generic subscription hands over CDR bytes, and a driver publishes them. The two paths
alternate call by call at the message's rate, in one run; the protocol's round trip is a
whole control cycle (pose, velocity, command), measured also without an input."""

from __future__ import annotations

import argparse
import functools
import os
import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from geometry_msgs.msg import PoseStamped, Twist
from nav2_pyif._ros_types import serialize, type_name_of
from nav2_pyif.client import ControllerClient
from nav2_pyif.common.option_types import positive_int
from nav2_pyif.common.zenoh_config import connect_to
from nav2_pyif_protocol.constants import Op
from sensor_msgs.msg import Image, LaserScan, PointCloud2, PointField

from nav2_pyif_bench.processes import free_port, peer_processes, ros_localhost_env
from nav2_pyif_bench.protocol_bench import TIMEOUTS, costmap, progress
from nav2_pyif_bench.stats import Summary

KEY = "nav2_pyif/bench/inputs"
#: input name -> rate [Hz]; the baseline: the control cycle alone at 20 Hz
RATES = {"scan": 20.0, "cloud": 10.0, "image": 10.0}


def messages() -> dict[str, Any]:
    """input name -> the message (random contents of the issue's sizes)."""
    rng = np.random.default_rng(0)
    scan = LaserScan(angle_min=-np.pi, angle_max=np.pi, range_min=0.05, range_max=12.0)
    scan.angle_increment = 2 * np.pi / 720
    scan.header.frame_id = "base_scan"
    scan.ranges = rng.uniform(0.1, 12.0, 720).astype(np.float32).tolist()
    points = 30_000
    cloud = PointCloud2(height=1, width=points, point_step=16, row_step=16 * points)
    cloud.header.frame_id = "lidar"
    cloud.fields = [
        PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
        for i, n in enumerate(("x", "y", "z", "intensity"))
    ]
    cloud.is_dense = True
    cloud.data = rng.random(points * 4, dtype=np.float32).tobytes()
    image = Image(height=480, width=640, encoding="rgb8", step=640 * 3)
    image.header.frame_id = "camera"
    image.data = rng.integers(0, 256, 480 * 640 * 3, np.uint8).tobytes()
    return {"scan": scan, "cloud": cloud, "image": image}


class TopicSide:
    """Publish serialized messages to the rclpy node, wait for its acknowledgement."""

    def __init__(self) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from std_msgs.msg import Header

        from nav2_pyif_bench.inputs_node import TOPICS
        from nav2_pyif_bench.rclpy_node import QOS

        rclpy.init()
        self.node = rclpy.create_node("pyif_bench_inputs_client")
        self.acked = threading.Event()
        self.node.create_subscription(
            Header, "/pyif_bench/input_ack", lambda _m: self.acked.set(), QOS
        )
        self.publishers = {
            name: self.node.create_publisher(cls, f"/pyif_bench/{name}", QOS)
            for name, (cls, _) in TOPICS.items()
        }
        self.executor = SingleThreadedExecutor()  # spun by the measuring thread itself
        self.executor.add_node(self.node)

    def wait_ready(self, cdr: dict[str, bytes], timeout: float = 30.0) -> None:
        deadline = time.monotonic() + timeout
        for name, pub in self.publishers.items():
            while True:
                if time.monotonic() > deadline:
                    raise RuntimeError("the rclpy inputs node did not come up (DDS discovery)")
                if pub.get_subscription_count():
                    try:
                        self.send(name, cdr[name], timeout=0.5)
                        break
                    except TimeoutError:
                        pass
                self.executor.spin_once(timeout_sec=0.05)

    def send(self, name: str, cdr: bytes, timeout: float = 5.0) -> int:
        self.acked.clear()
        start = time.perf_counter_ns()
        self.publishers[name].publish(cdr)  # rclpy publishes serialized bytes as they are
        deadline = time.monotonic() + timeout
        while not self.acked.is_set():
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError("the rclpy inputs node did not acknowledge")
            self.executor.spin_once(timeout_sec=remaining)
        return time.perf_counter_ns() - start

    def close(self) -> None:
        import rclpy

        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        rclpy.try_shutdown()  # type: ignore[attr-defined]


def paced(rate: float, calls: int, each: Callable[[], None]) -> None:
    """``each`` ``calls`` times on a fixed schedule of ``rate`` per second."""
    period, start = 1.0 / rate, time.monotonic()
    for i in range(calls):
        time.sleep(max(0.0, start + i * period - time.monotonic()))
        each()


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--calls",
        type=positive_int,
        default=200,
        help="messages per kind and path, >= 1 (default 200)",
    )
    parser.add_argument("--quick", action="store_true", help="20 messages per kind and path")


def run(args: argparse.Namespace) -> dict[str, Any]:
    calls = 20 if args.quick else args.calls
    msgs = messages()
    cdr = {name: serialize(msg) for name, msg in msgs.items()}
    types = {name: type_name_of(msg) for name, msg in msgs.items()}
    port, env = free_port(), ros_localhost_env()
    os.environ.update(env)  # this process publishes on the rclpy side
    host = [
        "-m", "nav2_pyif.server.cli", "--key", KEY, "--listen", f"tcp/127.0.0.1:{port}",
        "--log-level", "WARNING", "--planner", "nav2_pyif_bench.planners:InputReader",
    ]  # fmt: skip
    node = ["-m", "nav2_pyif_bench.inputs_node"]
    samples: dict[str, dict[str, list[int]]] = {"protocol": {}, "rclpy": {}}
    with peer_processes({"host": host, "node": node}, env) as peers:
        session = connect_to([f"tcp/127.0.0.1:{port}"], "peer")
        client = ControllerClient(session, KEY, costmap(10), timeouts=TIMEOUTS)
        topics = TopicSide()
        try:
            progress("waiting for the planner host and the rclpy node")
            if not client.wait_for_host(30):
                raise peers.not_up("the planner host")
            client.configure()
            client.activate()
            topics.wait_ready(cdr)
            pose, velocity = PoseStamped(), Twist()
            pose.header.frame_id = "odom"

            def cycle(name: str | None) -> int:
                # the body the C++ plugin sends: its generic subscription's CDR bytes as they are
                body = client.compute_body(pose, velocity)
                if name is not None:
                    received = time.time_ns()
                    body["inputs"] = [
                        {"name": name, "type": types[name], "stamp_ns": received, "cdr": cdr[name]}
                    ]
                start = time.perf_counter_ns()
                client.command_of(client._call(Op.COMPUTE_VELOCITY_COMMANDS, body))
                return time.perf_counter_ns() - start

            def both(name: str, ours: list[int], theirs: list[int]) -> None:
                ours.append(cycle(name))
                theirs.append(topics.send(name, cdr[name]))

            for _ in range(5):  # warm: the first decode of each type imports its support
                for name in msgs:
                    cycle(name)
                    topics.send(name, cdr[name])
            progress(f"the control cycle alone, {calls} calls at 20 Hz")
            base: list[int] = []
            paced(20.0, calls, lambda: base.append(cycle(None)))
            samples["protocol"]["none"] = base
            for name, rate in RATES.items():
                progress(f"{name}: {calls} messages at {rate:g} Hz through each path, alternating")
                ours: list[int] = []
                theirs: list[int] = []

                paced(rate, calls, functools.partial(both, name, ours, theirs))
                samples["protocol"][name], samples["rclpy"][name] = ours, theirs
            client.deactivate()
            client.cleanup()
        finally:
            topics.close()
            client.close()
            session.close()
    return {
        "calls": calls,
        "bytes": {name: len(data) for name, data in cdr.items()},
        "load_average": os.getloadavg()[0],
        "samples_ns": samples,
    }


LABELS = {
    "none": "(no input: the control cycle alone)",
    "scan": "LaserScan, 720 beams",
    "cloud": "PointCloud2, 30 000 points",
    "image": "Image, 640 x 480 rgb8",
}


def report(results: dict[str, Any]) -> str:
    samples = results["samples_ns"]
    lines = [
        f"{results['calls']} messages per kind and path, the paths alternating call by call; "
        f"load average {results['load_average']:.2f} at the end",
        "",
        f"  {'message':<38} {'CDR bytes':>9} {'rate':>6}   {'protocol cycle (ms)':>21}   "
        f"{'rclpy topic + ack (ms)':>22}",
        f"  {'':<38} {'':>9} {'':>6}   {'median':>10} {'p99':>10}   {'median':>10} {'p99':>11}",
    ]
    for name in ("none", *RATES):
        ours = Summary.of_ns(samples["protocol"][name])
        size = results["bytes"].get(name, 0)
        rate = RATES.get(name, 20.0)
        row = (
            f"  {LABELS[name]:<38} {size:>9} {rate:>4g} Hz   "
            f"{ours.median_us / 1e3:>10.2f} {ours.p99_us / 1e3:>10.2f}   "
        )
        if name in samples["rclpy"]:
            theirs = Summary.of_ns(samples["rclpy"][name])
            row += f"{theirs.median_us / 1e3:>10.2f} {theirs.p99_us / 1e3:>11.2f}"
        else:
            row += f"{'—':>10} {'—':>11}"
        lines.append(row)
    return "\n".join(lines)
