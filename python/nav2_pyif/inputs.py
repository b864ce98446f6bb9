"""A controller's extra inputs: the latest message of each topic listed in the plugin's
``inputs`` parameter, as ``self.inputs[name]``.

Types with a natural array form arrive as NumPy (views on the deserialized message's buffers
where the layout allows: no per-element Python objects); any other type is the rclpy message.

| type | ``self.inputs[name]`` |
|---|---|
| sensor_msgs/msg/LaserScan | Scan: ``ranges`` / ``intensities`` float32 (N,), ``angles`` (N,) |
| sensor_msgs/msg/PointCloud2 | Cloud: ``points`` structured (height * width,) by its fields |
| sensor_msgs/msg/Image | Image: ``pixels`` (H, W, C) of the encoding's dtype |
| nav_msgs/msg/Odometry | OdometryArrays: ``pose`` (7,), ``twist`` (6,) |
| sensor_msgs/msg/Imu | ImuArrays: ``orientation`` (4,), ``angular_velocity`` (3,), ... |

Each of those also has ``msg`` (the rclpy message), ``frame_id`` and ``stamp_ns`` (the header's).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from nav2_pyif_protocol.constants import MAX_INPUTS

from nav2_pyif._messages import stamp_to_ns
from nav2_pyif._ros_types import deserialize

F32 = npt.NDArray[np.float32]
F64 = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Scan:
    msg: Any
    frame_id: str
    stamp_ns: int
    ranges: F32  # [m]; +inf: no return (REP 117)
    intensities: F32  # empty when the driver sends none
    angles: F32  # [rad] of each beam in the scan's frame
    range_min: float
    range_max: float


@dataclass(frozen=True)
class Cloud:
    msg: Any
    frame_id: str
    stamp_ns: int
    points: np.ndarray  # structured: one field per PointField (x, y, z, intensity, ...)


@dataclass(frozen=True)
class Image:
    msg: Any
    frame_id: str
    stamp_ns: int
    encoding: str
    pixels: np.ndarray  # (H, W, C)


@dataclass(frozen=True)
class OdometryArrays:
    msg: Any
    frame_id: str
    stamp_ns: int
    child_frame_id: str
    pose: F64  # x, y, z [m], qx, qy, qz, qw in frame_id
    twist: F64  # vx, vy, vz [m/s], wx, wy, wz [rad/s] in child_frame_id


@dataclass(frozen=True)
class ImuArrays:
    msg: Any
    frame_id: str
    stamp_ns: int
    orientation: F64  # qx, qy, qz, qw
    angular_velocity: F64  # [rad/s]
    linear_acceleration: F64  # [m/s^2]


def _header(msg: Any) -> tuple[str, int]:
    return msg.header.frame_id, stamp_to_ns(msg.header.stamp)


def _f32(values: Any) -> F32:
    # rclpy gives float32[] fields as array.array('f'): a buffer, viewed without copying.
    return np.frombuffer(values, dtype=np.float32) if len(values) else np.zeros(0, np.float32)


def scan(msg: Any) -> Scan:
    ranges = _f32(msg.ranges)
    angles = msg.angle_min + msg.angle_increment * np.arange(len(ranges), dtype=np.float32)
    return Scan(
        msg, *_header(msg), ranges, _f32(msg.intensities), angles, msg.range_min, msg.range_max
    )


# sensor_msgs/PointField datatypes -> NumPy scalar types
_POINT_TYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}


def cloud(msg: Any) -> Cloud:
    order = ">" if msg.is_bigendian else "<"
    dtype = np.dtype(
        {
            "names": [f.name for f in msg.fields],
            "formats": [
                (order + _POINT_TYPES[f.datatype], (f.count,))
                if f.count > 1
                else order + _POINT_TYPES[f.datatype]
                for f in msg.fields
            ],
            "offsets": [f.offset for f in msg.fields],
            "itemsize": msg.point_step,
        }
    )
    rows = np.frombuffer(msg.data, dtype=np.uint8).reshape(msg.height, msg.row_step)
    used = rows[:, : msg.width * msg.point_step]  # a row may be padded beyond its points
    points = np.ascontiguousarray(used).view(dtype).reshape(msg.height * msg.width)
    return Cloud(msg, *_header(msg), points)


# sensor_msgs/image_encodings: name -> (channels, NumPy type)
_ENCODINGS = {
    "mono8": (1, "u1"),
    "mono16": (1, "u2"),
    "rgb8": (3, "u1"),
    "bgr8": (3, "u1"),
    "rgba8": (4, "u1"),
    "bgra8": (4, "u1"),
    "rgb16": (3, "u2"),
    "bgr16": (3, "u2"),
    "rgba16": (4, "u2"),
    "bgra16": (4, "u2"),
}


def _encoding(name: str) -> tuple[int, str]:
    if name in _ENCODINGS:
        return _ENCODINGS[name]
    # the generic ones: 8UC3, 32FC1, 16SC2, ...
    bits, kind, channels = name[:-3], name[-3:-2], name[-1:]
    if name[-2:-1] == "C" and bits.isdigit() and kind in "USF" and channels.isdigit():
        code = {"U": "u", "S": "i", "F": "f"}[kind] + str(int(bits) // 8)
        return int(channels), code
    raise ValueError(f"image encoding {name!r} has no array form here")


def image(msg: Any) -> Image:
    channels, code = _encoding(msg.encoding)
    dtype = np.dtype(code).newbyteorder(">" if msg.is_bigendian else "<")
    rows = np.frombuffer(msg.data, dtype=np.uint8).reshape(msg.height, msg.step)
    used = rows[:, : msg.width * channels * dtype.itemsize]
    pixels = np.ascontiguousarray(used).view(dtype).reshape(msg.height, msg.width, channels)
    return Image(msg, *_header(msg), msg.encoding, pixels)


def odometry(msg: Any) -> OdometryArrays:
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    v, w = msg.twist.twist.linear, msg.twist.twist.angular
    return OdometryArrays(
        msg,
        *_header(msg),
        msg.child_frame_id,
        np.array([p.x, p.y, p.z, q.x, q.y, q.z, q.w]),
        np.array([v.x, v.y, v.z, w.x, w.y, w.z]),
    )


def imu(msg: Any) -> ImuArrays:
    q, w, a = msg.orientation, msg.angular_velocity, msg.linear_acceleration
    return ImuArrays(
        msg,
        *_header(msg),
        np.array([q.x, q.y, q.z, q.w]),
        np.array([w.x, w.y, w.z]),
        np.array([a.x, a.y, a.z]),
    )


ARRAY_FORMS: dict[str, Callable[[Any], Any]] = {
    "sensor_msgs/msg/LaserScan": scan,
    "sensor_msgs/msg/PointCloud2": cloud,
    "sensor_msgs/msg/Image": image,
    "nav_msgs/msg/Odometry": odometry,
    "sensor_msgs/msg/Imu": imu,
}


def from_cdr(type_name: str, cdr: bytes) -> Any:
    """A serialized message -> its array form, or the rclpy message for other types."""
    msg = deserialize(type_name, cdr)
    form = ARRAY_FORMS.get(type_name)
    return form(msg) if form else msg


class Inputs(Mapping[str, Any]):
    """The latest value of each input, kept between calls (a scan at 10 Hz is sent once,
    then seen by the following cycles of a 20 Hz controller too)."""

    def __init__(self) -> None:
        self._values: dict[str, Any] = {}
        self._received_ns: dict[str, int] = {}
        self._types: dict[str, str] = {}
        #: the inputs that arrived with the current call
        self.updated: frozenset[str] = frozenset()

    def update(self, wire: list[dict[str, Any]]) -> None:
        """Decode the ``inputs`` of a compute_velocity_commands request (wire Input maps).
        A session keeps the latest of each name, so the names are bounded: the plugin's
        ``inputs`` parameter names a few, and a peer sending ever new ones would otherwise grow
        the session without end (a hostile one did)."""
        new = {item["name"] for item in wire} - self._values.keys()
        if len(self._values) + len(new) > MAX_INPUTS:
            raise ValueError(
                f"more than {MAX_INPUTS} input names in one session (new: "
                f"{', '.join(sorted(map(repr, new))[:5])}); a plugin's 'inputs' parameter "
                f"names at most {MAX_INPUTS}"
            )
        for item in wire:
            name = item["name"]
            self._values[name] = from_cdr(item["type"], item["cdr"])
            self._received_ns[name] = item["stamp_ns"]
            self._types[name] = item["type"]
        self.updated = frozenset(item["name"] for item in wire)

    def received_ns(self, name: str) -> int:
        """When the plugin received the latest ``name`` (the server's clock) [ns]."""
        return self._received_ns[name]

    def type_of(self, name: str) -> str:
        return self._types[name]

    def __getitem__(self, name: str) -> Any:
        try:
            return self._values[name]
        except KeyError:
            have = ", ".join(self._values) or "none yet"
            raise KeyError(
                f"no input {name!r} has arrived (have: {have}); list it in the plugin's "
                f"'inputs' parameter, and check its topic publishes"
            ) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)
