"""A small simulated robot for the Nav2 launch test: a unicycle that follows /cmd_vel, with a
map, TF and odometry, as Nav2's servers expect them.

- /map (nav_msgs/OccupancyGrid, transient local): 8 m x 8 m at 5 cm (--map-size: 50 m gives
  1000 x 1000 cells), centred on the origin, with a wall x = 1 m, y in [-0.6, 2.5] m between
  the start and the test's goals;
- TF map -> odom (static, identity) and odom -> base_link (the integrated pose, 50 Hz, or
  --rate);
- /odom (nav_msgs/Odometry) with the commanded velocity as the measured one;
- /ground_truth (geometry_msgs/PoseStamped): the robot's true pose in the map.
With --drift-step DY, odometry drifts as a real robot's does: every --drift-period seconds of
driving, until --drift-max, the odom frame moves DY metres along the map's y axis against the
true pose, and map -> odom (now published at 50 Hz) jumps by as much, as AMCL's corrections do.
/cmd_vel is read as controller_server publishes it by default: geometry_msgs/Twist on Humble
and Jazzy, TwistStamped from Kilted on (enable_stamped_cmd_vel); a command older than 0.5 s
stops the robot. With --scan, a laser on base_link publishes /scan
(sensor_msgs/LaserScan, 20 Hz, 181 beams over the front half, 4 m) ray-cast on the wall.

    python sim_robot.py [--x X --y Y --yaw YAW] [--rate HZ]
"""

from __future__ import annotations

import argparse
import math
import os
import signal
from typing import Any

import rclpy
from geometry_msgs.msg import PoseStamped, TransformStamped, Twist, TwistStamped
from nav_msgs.msg import OccupancyGrid, Odometry
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import LaserScan
from tf2_ros import StaticTransformBroadcaster, TransformBroadcaster

RATE_HZ = 50.0
# controller_server's enable_stamped_cmd_vel default: false up to Jazzy, true from Kilted on
STAMPED_CMD_VEL = os.environ.get("ROS_DISTRO", "jazzy") not in ("humble", "jazzy")
MAP_SIZE_M = 8.0
RESOLUTION = 0.05
WALL_X = 1.0
WALL_Y = (-0.6, 2.5)


def make_map(stamp: object, size_m: float = MAP_SIZE_M) -> OccupancyGrid:
    cells = round(size_m / RESOLUTION)
    grid = OccupancyGrid()
    grid.header.frame_id = "map"
    grid.header.stamp = stamp
    grid.info.resolution = RESOLUTION
    grid.info.width = grid.info.height = cells
    grid.info.origin.position.x = grid.info.origin.position.y = -size_m / 2
    grid.info.origin.orientation.w = 1.0
    data = [0] * (cells * cells)
    half = size_m / 2
    mx = int((WALL_X + half) / RESOLUTION)
    for my in range(int((WALL_Y[0] + half) / RESOLUTION), int((WALL_Y[1] + half) / RESOLUTION)):
        for dx in range(2):
            data[my * cells + mx + dx] = 100
    grid.data = data
    return grid


SCAN_BEAMS, SCAN_RANGE = 181, 4.0


def wall_range(x: float, y: float, heading: float) -> float:
    """Distance along a ray from (x, y) to the wall's near face (x = WALL_X, the robot's side),
    +inf when the ray misses it or is longer than SCAN_RANGE."""
    face = WALL_X if x < WALL_X else WALL_X + 2 * RESOLUTION
    dx = math.cos(heading)
    if abs(dx) < 1e-9 or (face - x) / dx <= 0:
        return math.inf
    distance = (face - x) / dx
    hit_y = y + distance * math.sin(heading)
    return distance if WALL_Y[0] <= hit_y <= WALL_Y[1] and distance <= SCAN_RANGE else math.inf


def transform(parent: str, child: str, stamp: object, x: float, y: float, yaw: float) -> Any:
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id, t.header.stamp = parent, child, stamp
    t.transform.translation.x, t.transform.translation.y = x, y
    t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return t


class SimRobot(Node):
    def __init__(
        self,
        x: float,
        y: float,
        yaw: float,
        drift: tuple[float, float, float] = (0, 1, 0),
        map_size_m: float = MAP_SIZE_M,
        scan: bool = False,
        rate_hz: float = RATE_HZ,
    ) -> None:
        super().__init__("sim_robot")
        self.rate_hz = rate_hz
        self.x, self.y, self.yaw = x, y, yaw  # the true pose, in the map
        self.drift_step, self.drift_period, self.drift_max = drift
        self.drift_y, self.driving_s = 0.0, 0.0
        self.cmd = Twist()
        self.cmd_time = self.get_clock().now()
        latched = QoSProfile(
            depth=1,
            durability=DurabilityPolicy.TRANSIENT_LOCAL,
            reliability=ReliabilityPolicy.RELIABLE,
        )
        self.map_pub = self.create_publisher(OccupancyGrid, "map", latched)
        self.map_pub.publish(make_map(self.get_clock().now().to_msg(), map_size_m))
        self.static_tf = StaticTransformBroadcaster(self)
        if not self.drift_step:
            self.static_tf.sendTransform(
                transform("map", "odom", self.get_clock().now().to_msg(), 0.0, 0.0, 0.0)
            )
        self.tf = TransformBroadcaster(self)
        self.truth_pub = self.create_publisher(PoseStamped, "ground_truth", 10)
        self.odom_pub = self.create_publisher(Odometry, "odom", 10)
        if STAMPED_CMD_VEL:
            self.create_subscription(TwistStamped, "cmd_vel", self.on_stamped_cmd, 10)
        else:
            self.create_subscription(Twist, "cmd_vel", self.on_cmd, 10)
        self.create_timer(1.0 / rate_hz, self.step)
        if scan:
            self.scan_pub = self.create_publisher(LaserScan, "scan", 10)
            self.create_timer(1.0 / 20.0, self.publish_scan)

    def publish_scan(self) -> None:
        scan = LaserScan()
        scan.header.frame_id, scan.header.stamp = "base_link", self.get_clock().now().to_msg()
        scan.angle_min, scan.angle_max = -math.pi / 2, math.pi / 2
        scan.angle_increment = math.pi / (SCAN_BEAMS - 1)
        scan.range_min, scan.range_max = 0.05, SCAN_RANGE
        scan.ranges = [
            wall_range(self.x, self.y, self.yaw + scan.angle_min + i * scan.angle_increment)
            for i in range(SCAN_BEAMS)
        ]
        self.scan_pub.publish(scan)

    def on_stamped_cmd(self, msg: TwistStamped) -> None:
        self.on_cmd(msg.twist)

    def on_cmd(self, msg: Twist) -> None:
        self.cmd = msg
        self.cmd_time = self.get_clock().now()

    def step(self) -> None:
        now = self.get_clock().now()
        if (now - self.cmd_time).nanoseconds > 500_000_000:
            self.cmd = Twist()
        dt = 1.0 / self.rate_hz
        v, w = self.cmd.linear.x, self.cmd.angular.z
        self.x += v * math.cos(self.yaw) * dt
        self.y += v * math.sin(self.yaw) * dt
        self.yaw = math.atan2(math.sin(self.yaw + w * dt), math.cos(self.yaw + w * dt))
        if self.drift_step and abs(v) + abs(w) > 1e-3:
            self.driving_s += dt
            if self.driving_s >= self.drift_period and abs(self.drift_y) < self.drift_max:
                self.driving_s = 0.0
                self.drift_y += self.drift_step
        stamp = now.to_msg()
        odom_y = self.y - self.drift_y  # odometry's idea of the pose
        if self.drift_step:
            self.tf.sendTransform(transform("map", "odom", stamp, 0.0, self.drift_y, 0.0))
        self.tf.sendTransform(transform("odom", "base_link", stamp, self.x, odom_y, self.yaw))
        truth = PoseStamped()
        truth.header.frame_id, truth.header.stamp = "map", stamp
        truth.pose.position.x, truth.pose.position.y = self.x, self.y
        self.truth_pub.publish(truth)
        odom = Odometry()
        odom.header.frame_id, odom.child_frame_id, odom.header.stamp = "odom", "base_link", stamp
        odom.pose.pose.position.x, odom.pose.pose.position.y = self.x, odom_y
        odom.pose.pose.orientation.z = math.sin(self.yaw / 2)
        odom.pose.pose.orientation.w = math.cos(self.yaw / 2)
        odom.twist.twist = self.cmd
        self.odom_pub.publish(odom)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--x", type=float, default=0.0)
    parser.add_argument("--y", type=float, default=0.0)
    parser.add_argument("--yaw", type=float, default=0.0)
    parser.add_argument("--drift-step", type=float, default=0.0, help="[m] (default 0: none)")
    parser.add_argument("--drift-period", type=float, default=1.5, help="[s] of driving")
    parser.add_argument("--drift-max", type=float, default=0.4, help="[m] in all")
    parser.add_argument("--map-size", type=float, default=MAP_SIZE_M, help="[m] square")
    parser.add_argument("--scan", action="store_true", help="publish /scan (LaserScan)")
    parser.add_argument(
        "--rate", type=float, default=RATE_HZ, help="[Hz] of the pose, TF and odometry"
    )
    args = parser.parse_args()
    rclpy.init()
    drift = (args.drift_step, args.drift_period, args.drift_max)
    node = SimRobot(args.x, args.y, args.yaw, drift, args.map_size, args.scan, args.rate)
    signal.signal(signal.SIGTERM, lambda *_: rclpy.try_shutdown())
    try:
        rclpy.spin(node)
    except Exception:  # shutdown from the signal handler
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
