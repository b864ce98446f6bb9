"""Path smoothing in NumPy: what Nav2's SimpleSmoother does (nav2_smoother, simple_smoother.cpp
and smoother_utils.hpp), on whole arrays instead of pose by pose.

Each point is pulled towards its neighbours (``w_smooth``) and towards where it was
(``w_data``) until a sweep changes the path by less than ``tolerance``; the end points of
each directional segment (split at cusps, where the path reverses, and at turns in place) stay
fixed; a sweep that would put a point on a lethal cell is undone and the last admissible path
returned; ``refinement_num`` more passes start from the result when ``do_refinement``. The
sweep updates every other point, then the rest with their updated neighbours (red-black
Gauss-Seidel): the fixed point Nav2's sequential sweep converges to, at NumPy speed.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
# (K, 2) world points -> (K,) costs; Nav2's convention: > 252 lethal or inscribed, 255 unknown
CostLookup = Callable[[FloatArray], npt.NDArray[np.uint8]]
MAX_NON_OBSTACLE, NO_INFORMATION = 252, 255


@dataclass(frozen=True)
class SmootherSettings:
    """Nav2 SimpleSmoother's parameters, with its defaults."""

    tolerance: float = 1e-10
    max_its: int = 1000
    w_data: float = 0.2
    w_smooth: float = 0.3
    do_refinement: bool = True
    refinement_num: int = 2


class SmoothingTimedOut(Exception):
    """``max_time`` ran out; ``path`` is the last admissible path reached."""

    def __init__(self, message: str, path: FloatArray) -> None:
        super().__init__(message)
        self.path = path


def directional_segments(poses: FloatArray) -> list[tuple[int, int]]:
    """(start, end) index pairs, inclusive, of the path's pieces driven in one direction:
    split where consecutive steps point against each other (a cusp) and at turns in place."""
    xy, yaw = poses[:, :2], poses[:, 2]
    steps = np.diff(xy, axis=0)
    if len(steps) < 2:
        return [(0, len(poses) - 1)]
    reverses = np.einsum("ij,ij->i", steps[:-1], steps[1:]) < 0.0
    dyaw = np.angle(np.exp(1j * (yaw[2:] - yaw[1:-1])))
    in_place = np.all(np.abs(steps[1:]) < 1e-4, axis=1) & (np.abs(dyaw) > 1e-4)
    cuts = [0]
    for idx in np.flatnonzero(reverses | in_place) + 1:  # index of the middle pose
        cuts.extend([int(idx)] * (1 + int(reverses[idx - 1] and in_place[idx - 1])))
    cuts.append(len(poses) - 1)
    return list(itertools.pairwise(cuts))


def approximate_orientations(poses: FloatArray) -> FloatArray:
    """Yaw of each pose along its step to the next (turned by pi on a reversing segment, one
    whose second pose faces against its travel); the last pose and duplicates keep theirs."""
    out: FloatArray = np.array(poses, dtype=np.float64, copy=True)
    if len(poses) < 3:
        return out
    d0 = poses[2, :2] - poses[1, :2]
    reversing = abs(_angle_diff(poses[1, 2], math.atan2(d0[1], d0[0]))) > math.pi / 2
    steps = np.diff(poses[:, :2], axis=0)
    moving = np.any(np.abs(steps) >= 1e-4, axis=1)
    theta = np.arctan2(steps[:, 1], steps[:, 0]) + (math.pi if reversing else 0.0)
    out[:-1, 2] = np.where(moving, np.angle(np.exp(1j * theta)), poses[:-1, 2])
    return out


def _angle_diff(a: float, b: float) -> float:
    return math.atan2(math.sin(b - a), math.cos(b - a))


def _sweep(original: FloatArray, path: FloatArray, settings: SmootherSettings) -> float:
    """One red-black pass over the interior points, in place; the summed change."""
    before = path[1:-1].copy()
    for first in (1, 2):
        i = np.arange(first, len(path) - 1, 2)
        path[i] += settings.w_data * (original[i] - path[i]) + settings.w_smooth * (
            path[i + 1] + path[i - 1] - 2.0 * path[i]
        )
    return float(np.abs(path[1:-1] - before).sum())


def _admissible(path: FloatArray, costs: CostLookup | None) -> bool:
    if costs is None or len(path) < 3:
        return True
    c = costs(path[1:-1])
    return not bool(np.any((c > MAX_NON_OBSTACLE) & (c != NO_INFORMATION)))


def smooth_segment(
    xy: FloatArray, settings: SmootherSettings, costs: CostLookup | None, deadline: float
) -> tuple[FloatArray, int]:
    """The smoothed (N, 2) points of one directional segment and the sweeps it took; raises
    SmoothingTimedOut past ``deadline`` (time.monotonic())."""
    original = np.asarray(xy, dtype=np.float64)
    path, last = original.copy(), original.copy()
    sweeps = 0
    for _ in range(1 + (settings.refinement_num if settings.do_refinement else 0)):
        change, its = settings.tolerance, 0
        while change >= settings.tolerance:
            its += 1
            if its >= settings.max_its:
                return last, sweeps  # as Nav2: the last admissible path, with a warning there
            if time.monotonic() > deadline:
                raise SmoothingTimedOut("smoothing exceeded its allowed duration", last)
            change = _sweep(original, path, settings)
            sweeps += 1
            if not _admissible(path, costs):
                return last, sweeps  # the last path before a point was put in collision
            last = path.copy()
        original = path.copy()  # a refinement pass pulls towards the smoothed path
    return path, sweeps


def smooth_path(
    poses: npt.ArrayLike,
    settings: SmootherSettings = SmootherSettings(),
    costs: CostLookup | None = None,
    max_time: float = math.inf,
) -> FloatArray:
    """(N, 3) x, y, yaw -> the smoothed (N, 3) path: segments of more than three poses
    smoothed, orientations re-derived from the new points. Raises SmoothingTimedOut (with the
    path smoothed so far) when ``max_time`` seconds run out."""
    out = np.array(poses, dtype=np.float64, copy=True)
    if out.ndim != 2 or out.shape[1] != 3:
        raise ValueError(f"poses must be (N, 3) x, y, yaw; got shape {out.shape}")
    deadline = time.monotonic() + max_time
    for start, end in directional_segments(out):
        if end - start <= 3:
            continue
        segment = out[start : end + 1]
        try:
            xy, _ = smooth_segment(segment[:, :2], settings, costs, deadline)
        except SmoothingTimedOut as exc:
            segment[:, :2] = exc.path
            out[start : end + 1] = approximate_orientations(segment)
            raise SmoothingTimedOut(str(exc), out) from None
        segment[:, :2] = xy
        out[start : end + 1] = approximate_orientations(segment)
    return out
