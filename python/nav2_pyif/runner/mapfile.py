"""Maps in map_server format (YAML + PGM), read and written without extra dependencies.

The YAML keys are map_server's (image, resolution, origin, negate, occupied_thresh,
free_thresh, mode); ``nav2_pyif: {start: [x, y, yaw], goal: [x, y, yaw]}`` adds a default task.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt
import yaml

FREE, UNKNOWN, OCCUPIED = 0, -1, 100


class MapError(Exception):
    """A map that cannot be used, with the reason."""


@dataclass
class OccupancyMap:
    """occupancy[my, mx] in {0 free, 100 occupied, -1 unknown}; row 0 is the bottom (y min)."""

    occupancy: npt.NDArray[np.int8]
    resolution: float
    origin_x: float
    origin_y: float
    name: str = "map"
    start: tuple[float, float, float] | None = None
    goal: tuple[float, float, float] | None = None

    @property
    def size_x(self) -> int:
        return int(self.occupancy.shape[1])

    @property
    def size_y(self) -> int:
        return int(self.occupancy.shape[0])


def read_pgm(path: Path) -> npt.NDArray[np.uint8]:
    """P5 (binary) or P2 (ASCII) PGM, 8-bit. Row 0 is the image's top."""
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise MapError(f"cannot read map image {path}: {exc.strerror}") from exc
    header = re.match(rb"(P[25])\s+(?:#.*\s+)*(\d+)\s+(?:#.*\s+)*(\d+)\s+(?:#.*\s+)*(\d+)\s", data)
    if header is None:
        raise MapError(f"{path} is not a PGM image (P2/P5 header expected)")
    magic, width, height, maxval = header.group(1), *(int(header.group(i)) for i in (2, 3, 4))
    if maxval > 255:
        raise MapError(f"{path}: 16-bit PGM (maxval {maxval}) is not supported")
    body = data[header.end() :]
    if magic == b"P5":
        if len(body) < width * height:
            raise MapError(f"{path}: truncated ({len(body)} of {width * height} pixel bytes)")
        pixels = np.frombuffer(body[: width * height], np.uint8)
    else:
        values = body.split()
        if len(values) < width * height:
            raise MapError(f"{path}: truncated ({len(values)} of {width * height} pixels)")
        pixels = np.array([int(v) for v in values[: width * height]], np.uint8)
    image = pixels.reshape(height, width)
    if maxval != 255:
        image = (image.astype(np.float64) * 255.0 / maxval).round().astype(np.uint8)
    return image


def write_pgm(path: Path, image: npt.NDArray[np.uint8]) -> None:
    height, width = image.shape
    path.write_bytes(f"P5\n{width} {height}\n255\n".encode() + image.astype(np.uint8).tobytes())


def load_map(yaml_path: Path) -> OccupancyMap:
    """Read a map_server YAML and its image (trinary mode, as map_server does)."""
    if not yaml_path.is_file():
        raise MapError(f"map file {yaml_path} does not exist")
    try:
        meta = yaml.safe_load(yaml_path.read_text())
    except yaml.YAMLError as exc:
        raise MapError(f"{yaml_path} is not valid YAML: {exc}") from exc
    if not isinstance(meta, dict):
        raise MapError(f"{yaml_path}: expected a YAML mapping")
    missing = [k for k in ("image", "resolution", "origin") if k not in meta]
    if missing:
        raise MapError(f"{yaml_path}: missing key(s) {', '.join(missing)}")
    image = read_pgm((yaml_path.parent / str(meta["image"])).resolve())
    negate = bool(meta.get("negate", 0))
    occupied_thresh = float(meta.get("occupied_thresh", 0.65))
    free_thresh = float(meta.get("free_thresh", 0.25))
    shade = image.astype(np.float64) / 255.0
    probability = shade if negate else 1.0 - shade
    occupancy = np.full(image.shape, UNKNOWN, np.int8)
    occupancy[probability > occupied_thresh] = OCCUPIED
    occupancy[probability < free_thresh] = FREE
    origin = meta["origin"]
    task = meta.get("nav2_pyif") or {}
    return OccupancyMap(
        occupancy=np.flipud(occupancy).copy(),  # image top row is the map's last row
        resolution=float(meta["resolution"]),
        origin_x=float(origin[0]),
        origin_y=float(origin[1]),
        name=yaml_path.stem,
        start=_pose3(task.get("start")),
        goal=_pose3(task.get("goal")),
    )


def _pose3(value: object) -> tuple[float, float, float] | None:
    if value is None:
        return None
    if not isinstance(value, (list, tuple)) or len(value) not in (2, 3):
        raise MapError(f"task pose {value!r} must be [x, y] or [x, y, yaw]")
    x, y, *rest = (float(v) for v in value)
    return (x, y, rest[0] if rest else 0.0)


def save_map(
    path: Path,
    occupancy: npt.NDArray[np.int8],
    resolution: float,
    origin: tuple[float, float],
    start: tuple[float, float, float],
    goal: tuple[float, float, float],
) -> None:
    """Write ``path`` (.yaml) and its .pgm the way map_saver does (trinary)."""
    image = np.full(occupancy.shape, 205, np.uint8)
    image[occupancy == FREE] = 254
    image[occupancy == OCCUPIED] = 0
    write_pgm(path.with_suffix(".pgm"), np.flipud(image))
    meta = {
        "image": path.with_suffix(".pgm").name,
        "mode": "trinary",
        "resolution": resolution,
        "origin": [origin[0], origin[1], 0.0],
        "negate": 0,
        "occupied_thresh": 0.65,
        "free_thresh": 0.196,  # 205 (unknown) stays unknown, as in ROS map_saver maps
        "nav2_pyif": {
            "start": [start[0], start[1], round(start[2], 4)],
            "goal": [goal[0], goal[1], round(goal[2], 4)],
        },
    }
    path.write_text(yaml.safe_dump(meta, sort_keys=False))


def yaw_deg(yaw: float) -> float:
    return math.degrees(yaw)
