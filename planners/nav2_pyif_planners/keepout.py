"""Keep-out polygons on a costmap window, in NumPy: which cells a set of polygons covers (how
a layer's costs then combine with the master grid's is ``nav2_pyif.Combine.apply``)."""

from __future__ import annotations

import ast

import numpy as np
import numpy.typing as npt

__all__ = ["NO_INFORMATION", "parse_polygons", "polygon_mask"]

FloatArray = npt.NDArray[np.float64]
ByteArray = npt.NDArray[np.uint8]


NO_INFORMATION = 255


def parse_polygons(text: str) -> list[FloatArray]:
    """Polygons from a parameter string, as Nav2 writes footprints: "[[[x, y], [x, y], ...],
    [[x, y], ...]]" (a list of polygons, each of at least three [x, y] points, in metres)."""
    try:
        value = ast.literal_eval(text) if text.strip() else []
    except (ValueError, SyntaxError) as exc:
        raise ValueError(f"polygons {text!r} are not a list of [[x, y], ...] lists") from exc
    polygons = []
    for i, polygon in enumerate(value):
        points = np.asarray(polygon, dtype=np.float64)
        if points.ndim != 2 or points.shape[1] != 2 or len(points) < 3:
            raise ValueError(f"polygon {i} needs at least three [x, y] points, got {polygon!r}")
        polygons.append(points)
    return polygons


def polygon_mask(
    polygons: list[FloatArray],
    origin: tuple[float, float],
    resolution: float,
    shape: tuple[int, int],
) -> npt.NDArray[np.bool_]:
    """(rows, cols) mask of the cells whose centres lie inside any polygon (even-odd rule);
    the window's cell (0, 0) has its corner at ``origin`` (world metres). Each polygon is
    tested only on the cells of its bounding box: a 400 x 400 window with a few small zones
    costs what their boxes cost."""
    rows, cols = shape
    mask = np.zeros(shape, dtype=bool)
    for polygon in polygons:
        (x_lo, y_lo), (x_hi, y_hi) = polygon.min(axis=0), polygon.max(axis=0)
        c0 = max(0, int(np.floor((x_lo - origin[0]) / resolution - 0.5)))
        c1 = min(cols, int(np.ceil((x_hi - origin[0]) / resolution + 0.5)))
        r0 = max(0, int(np.floor((y_lo - origin[1]) / resolution - 0.5)))
        r1 = min(rows, int(np.ceil((y_hi - origin[1]) / resolution + 0.5)))
        if c0 >= c1 or r0 >= r1:
            continue  # the polygon misses the window
        cx = origin[0] + (np.arange(c0, c1) + 0.5) * resolution
        cy = origin[1] + (np.arange(r0, r1) + 0.5) * resolution
        px, py = np.meshgrid(cx, cy)
        inside = np.zeros(px.shape, dtype=bool)
        x0, y0 = polygon[:, 0], polygon[:, 1]
        x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
        for ax, ay, bx, by in zip(x0, y0, x1, y1, strict=True):
            if ay == by:
                continue  # a horizontal edge crosses no horizontal ray
            crosses = (ay > py) != (by > py)
            at_x = ax + (py - ay) * (bx - ax) / (by - ay)
            inside ^= crosses & (px < at_x)
        mask[r0:r1, c0:c1] |= inside
    return mask
