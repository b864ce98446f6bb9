"""Draw the bundled maps. Deterministic: re-running gives the committed files.

python -m nav2_pyif.runner.maps.generate
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from nav2_pyif.runner.mapfile import FREE, OCCUPIED, save_map

RESOLUTION = 0.05


class Canvas:
    def __init__(self, width_m: float, height_m: float) -> None:
        self.grid = np.full(
            (round(height_m / RESOLUTION), round(width_m / RESOLUTION)), FREE, np.int8
        )

    def box(self, x0: float, y0: float, x1: float, y1: float, value: int = OCCUPIED) -> None:
        """Fill the rectangle [x0, x1] x [y0, y1] (metres)."""
        c0, c1 = round(min(x0, x1) / RESOLUTION), round(max(x0, x1) / RESOLUTION)
        r0, r1 = round(min(y0, y1) / RESOLUTION), round(max(y0, y1) / RESOLUTION)
        self.grid[r0 : max(r1, r0 + 1), c0 : max(c1, c0 + 1)] = value

    def walls(self, thickness: float = 0.15) -> None:
        h, w = self.grid.shape[0] * RESOLUTION, self.grid.shape[1] * RESOLUTION
        self.box(0, 0, w, thickness)
        self.box(0, h - thickness, w, h)
        self.box(0, 0, thickness, h)
        self.box(w - thickness, 0, w, h)


def office() -> Canvas:
    c = Canvas(20.0, 14.0)
    c.walls()
    # corridor between y = 6 and y = 8; walls with 1 m doorways into the rooms
    for y in (6.0, 8.0):
        c.box(0, y - 0.075, 20, y + 0.075)
    for x in (2.0, 7.5, 12.5, 17.5):  # doorways
        c.box(x - 0.5, 5.9, x + 0.5, 6.1, FREE)
        c.box(x - 0.5, 7.9, x + 0.5, 8.1, FREE)
    for x in (5.0, 10.0, 15.0):  # room dividers
        c.box(x - 0.075, 0, x + 0.075, 6.0)
        c.box(x - 0.075, 8.0, x + 0.075, 14.0)
    # furniture: desks and a meeting table
    for x0, y0, x1, y1 in [
        (0.8, 3.5, 2.6, 4.3),
        (3.0, 1.0, 4.2, 2.0),
        (6.0, 2.5, 8.5, 3.3),
        (11.0, 1.0, 11.8, 4.5),
        (13.5, 3.0, 14.3, 5.0),
        (16.0, 2.0, 19.0, 2.8),
        (1.0, 10.0, 3.5, 11.0),
        (6.5, 10.5, 8.5, 12.5),
        (11.0, 9.5, 14.0, 10.3),
        (16.0, 10.0, 16.8, 12.0),
        (8.5, 6.5, 9.0, 7.0),
    ]:
        c.box(x0, y0, x1, y1)
    return c


def cluttered() -> Canvas:
    c = Canvas(14.0, 10.0)
    c.walls()
    rng = np.random.default_rng(7)
    boxes = 0
    while boxes < 22:
        x, y = rng.uniform(1.6, 8.2), rng.uniform(0.6, 9.0)
        w, h = rng.uniform(0.3, 0.8), rng.uniform(0.3, 0.8)
        if math.hypot(x - 1.0, y - 1.0) < 1.2 or math.hypot(x - 9.0, y - 5.0) < 1.2:
            continue  # keep the start and the corridor entrance clear
        c.box(x, y, x + w, y + h)
        boxes += 1
    # a wall across x = 9..13 with a 0.8 m zig-zag corridor through it
    c.box(9.0, 0.15, 13.0, 9.85)
    lane = 0.4  # half-width of the 0.8 m corridor
    for x0, y0, x1, y1 in [
        (9.0, 5.0 - lane, 10.5 + lane, 5.0 + lane),
        (10.5 - lane, 2.5 - lane, 10.5 + lane, 5.0 + lane),
        (10.5 - lane, 2.5 - lane, 12.0 + lane, 2.5 + lane),
        (12.0 - lane, 2.5 - lane, 12.0 + lane, 8.0 + lane),
        (12.0 - lane, 8.0 - lane, 13.0, 8.0 + lane),
    ]:
        c.box(x0, y0, x1, y1, FREE)
    return c


def main() -> None:
    out = Path(__file__).parent
    save_map(
        out / "office.yaml",
        office().grid,
        RESOLUTION,
        (0.0, 0.0),
        start=(2.0, 2.5, 0.0),
        goal=(17.5, 12.0, math.pi / 2),
    )
    save_map(
        out / "cluttered.yaml",
        cluttered().grid,
        RESOLUTION,
        (0.0, 0.0),
        start=(1.0, 1.0, 0.0),
        goal=(13.5, 8.0, 0.0),
    )
    print(f"wrote office and cluttered maps to {out}")


if __name__ == "__main__":
    main()
