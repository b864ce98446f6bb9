"""The sensor-input launch test's controller: the reference pure pursuit that will not drive
without a laser scan (``inputs["scan"]``, shipped by the plugin from /scan) and slows down as
the nearest return ahead gets closer; it publishes that return as a debug output
(``FollowPath/nearest_return``, a PointStamped in the costmap's frame) beside its local plan
(``FollowPath/local_plan``)."""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np
from nav2_pyif import NoValidControl
from nav2_pyif.inputs import Scan
from nav2_pyif_planners.pure_pursuit import RegulatedPurePursuit


class ScanGuard(RegulatedPurePursuit):
    debug_outputs: ClassVar[dict[str, str]] = {
        **RegulatedPurePursuit.debug_outputs,
        "nearest_return": "geometry_msgs/msg/PointStamped",
        "local_plan": "nav_msgs/msg/Path",
    }

    def configure(self) -> None:
        super().configure()
        self.slow_within = self.params.declare("slow_within", 0.8, "slow down nearer [m]")

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        if "scan" not in self.inputs:
            raise NoValidControl("no laser scan received yet (input 'scan')")
        scan: Scan = self.inputs["scan"]
        cmd = super().compute_velocity_commands(pose, velocity, goal_checker)
        ahead = np.abs(scan.angles) < math.radians(30)
        finite = ahead & np.isfinite(scan.ranges)
        x, y = pose.pose.position.x, pose.pose.position.y
        q = pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        if finite.any():
            i = int(np.flatnonzero(finite)[np.argmin(scan.ranges[finite])])
            r, a = float(scan.ranges[i]), float(scan.angles[i])
            self.publish_debug(
                "nearest_return", np.array([x + r * math.cos(yaw + a), y + r * math.sin(yaw + a)])
            )
            cmd.twist.linear.x *= min(1.0, max(0.3, r / self.slow_within))
        if self.plan is not None and len(self.plan):
            self.publish_debug("local_plan", self.plan.xy_yaw[:20])
        return cmd
