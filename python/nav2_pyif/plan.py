"""A path as NumPy first: what ``set_plan`` receives and what ``create_plan`` may return.

A ``Plan`` reads like a nav_msgs/Path (``header``, ``poses`` as PoseStamped, built lazily on
first use) so code written against the message works, while NumPy code uses ``array`` and
``xy_yaw`` at no conversion cost.
"""

from __future__ import annotations

from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt
from nav2_pyif_protocol.arrays import (
    FloatArray,
    pack_poses,
    poses_from_xy_yaw,
    quaternion_to_yaw,
    unpack_poses,
)

from nav2_pyif._messages import ns_to_stamp, stamp_to_ns
from nav2_pyif.geometry import arc_lengths, path_length


class Plan:
    def __init__(self, array: npt.ArrayLike, frame_id: str = "map", stamp_ns: int = 0) -> None:
        """``array``: (N, 7) x, y, z [m], qx, qy, qz, qw; or (N, 3) x, y, yaw; or (N, 2) x, y."""
        a = np.asarray(array, dtype=np.float64)
        self.array: FloatArray = np.zeros((0, 7)) if a.size == 0 else poses_from_xy_yaw(a)
        self.frame_id = frame_id
        self.stamp_ns = int(stamp_ns)

    @classmethod
    def from_wire(cls, wire: dict[str, Any]) -> Plan:
        plan = cls.__new__(cls)
        plan.array = unpack_poses(wire["poses"])  # zero-copy, read-only
        plan.frame_id = wire["frame_id"]
        plan.stamp_ns = wire["stamp_ns"]
        return plan

    def to_wire(self) -> dict[str, Any]:
        return {
            "frame_id": self.frame_id,
            "stamp_ns": self.stamp_ns,
            "poses": pack_poses(self.array),
        }

    @classmethod
    def from_msg(cls, msg: Any) -> Plan:
        """nav_msgs/Path -> Plan."""
        rows = [
            (
                p.pose.position.x,
                p.pose.position.y,
                p.pose.position.z,
                p.pose.orientation.x,
                p.pose.orientation.y,
                p.pose.orientation.z,
                p.pose.orientation.w,
            )
            for p in msg.poses
        ]
        return cls(
            np.array(rows, dtype=np.float64).reshape(-1, 7),
            msg.header.frame_id,
            stamp_to_ns(msg.header.stamp),
        )

    def __len__(self) -> int:
        return int(self.array.shape[0])

    @cached_property
    def xy_yaw(self) -> FloatArray:
        """(N, 3) x, y [m], yaw [rad]."""
        out = np.empty((len(self), 3))
        out[:, :2] = self.array[:, :2]
        out[:, 2] = quaternion_to_yaw(self.array[:, 3:])
        return out

    @cached_property
    def along(self) -> FloatArray:
        """(N,) arc length [m] from the first pose to each (0 for the first): computed once
        per plan, not in every control cycle."""
        return arc_lengths(self.array)

    @property
    def xy(self) -> FloatArray:
        """(N, 2) x, y [m] (a view)."""
        return self.array[:, :2]

    def length(self) -> float:
        """Arc length [m] (``nav2_pyif.path_length`` of ``xy``)."""
        return path_length(self.xy)

    # --- nav_msgs/Path look-alike ---------------------------------------------------------
    @cached_property
    def header(self) -> Any:
        from std_msgs.msg import Header

        return Header(frame_id=self.frame_id, stamp=ns_to_stamp(self.stamp_ns))

    @cached_property
    def poses(self) -> list[Any]:
        """The poses as geometry_msgs/PoseStamped (built on first access: ~10 us each)."""
        from geometry_msgs.msg import PoseStamped

        out = []
        for x, y, z, qx, qy, qz, qw in self.array.tolist():
            msg = PoseStamped()
            msg.header = self.header
            msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = x, y, z
            o = msg.pose.orientation
            o.x, o.y, o.z, o.w = qx, qy, qz, qw
            out.append(msg)
        return out

    def to_msg(self) -> Any:
        from nav_msgs.msg import Path

        return Path(header=self.header, poses=self.poses)

    def __repr__(self) -> str:
        return f"Plan({len(self)} poses, frame {self.frame_id!r})"
