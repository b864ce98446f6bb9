"""Packed float64 arrays on the wire <-> NumPy, without copies where NumPy allows.

Poses are x, y, z, qx, qy, qz, qw; byte order little-endian (``<f8``) on every machine.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

F64 = np.dtype("<f8")
FloatArray = npt.NDArray[np.float64]
ByteArray = npt.NDArray[np.uint8]


def pack_poses(poses: npt.ArrayLike) -> bytes:
    """(N, 7) float64 -> bytes (N * 56)."""
    array = np.ascontiguousarray(poses, dtype=F64)
    if array.ndim != 2 or array.shape[1] != 7:
        raise ValueError(f"poses must be (N, 7): x, y, z, qx, qy, qz, qw; got {array.shape}")
    return array.tobytes()


def unpack_poses(data: bytes) -> FloatArray:
    """bytes (N * 56) -> read-only (N, 7) float64 view."""
    if len(data) % 56:
        raise ValueError(f"path data has {len(data)} bytes, not a multiple of 56 (7 x float64)")
    return np.frombuffer(data, dtype=F64).reshape(-1, 7)


def pack_xy(points: npt.ArrayLike) -> bytes:
    """(K, 2) float64 -> bytes (footprints)."""
    array = np.ascontiguousarray(points, dtype=F64).reshape(-1, 2)
    return array.tobytes()


def unpack_xy(data: bytes) -> FloatArray:
    if len(data) % 16:
        raise ValueError(f"footprint data has {len(data)} bytes, not a multiple of 16")
    return np.frombuffer(data, dtype=F64).reshape(-1, 2)


def costmap_grid(data: bytes, size_x: int, size_y: int) -> ByteArray:
    """Costmap bytes -> read-only (size_y, size_x) uint8 view: ``grid[my, mx]``."""
    if size_x < 0 or size_y < 0 or len(data) != size_x * size_y:
        raise ValueError(
            f"costmap data has {len(data)} bytes; size {size_x} x {size_y} needs {size_x * size_y}"
        )
    return np.frombuffer(data, dtype=np.uint8).reshape(size_y, size_x)


def yaw_to_quaternion(yaw: npt.ArrayLike) -> FloatArray:
    """yaw [rad] (N,) -> (N, 4) qx, qy, qz, qw for rotations about z."""
    half = 0.5 * np.asarray(yaw, dtype=np.float64)
    out = np.zeros((*half.shape, 4), dtype=np.float64)
    out[..., 2] = np.sin(half)
    out[..., 3] = np.cos(half)
    return out


def quaternion_to_yaw(q: npt.ArrayLike) -> FloatArray:
    """(..., 4) qx, qy, qz, qw -> yaw [rad] (...,)."""
    qa = np.asarray(q, dtype=np.float64)
    x, y, z, w = qa[..., 0], qa[..., 1], qa[..., 2], qa[..., 3]
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def poses_from_xy_yaw(xy_yaw: npt.ArrayLike) -> FloatArray:
    """(N, 2) or (N, 3) x, y [, yaw] -> (N, 7). Missing yaw: each pose faces the next one."""
    a = np.asarray(xy_yaw, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] not in (2, 3, 7):
        raise ValueError(f"expected (N, 2), (N, 3) or (N, 7) poses; got {a.shape}")
    if a.shape[1] == 7:
        return np.ascontiguousarray(a)
    if a.shape[1] == 3:
        yaw = a[:, 2]
    else:
        yaw = np.zeros(len(a))
        if len(a) > 1:
            d = np.diff(a, axis=0)
            yaw[:-1] = np.arctan2(d[:, 1], d[:, 0])
            yaw[-1] = yaw[-2]
    out = np.zeros((len(a), 7), dtype=np.float64)
    out[:, :2] = a[:, :2]
    out[:, 3:] = yaw_to_quaternion(yaw)
    return out
