"""The scenarios of ``nav2-pyif eval``: a map (map_server YAML + PGM) with a start and a goal.

Three sources: the bundled maps, the user's own maps (their ``nav2_pyif: {start, goal}``
block, or ``--start``/``--goal``), and generated ones: random boxes at a set density between a
start on the left and a goal on the right, drawn from a seed (the same seed gives the same
map, on any machine), as BARN's worlds; a generated world the robot cannot cross is drawn
again from the next seed.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from nav2_pyif.runner.mapfile import FREE, OCCUPIED, MapError, OccupancyMap, load_map, save_map
from nav2_pyif.runner.maps import BUNDLED, map_path
from nav2_pyif.runner.maps.generate import RESOLUTION, Canvas
from nav2_pyif.runner.robot import DEFAULT_FOOTPRINT

Pose3 = tuple[float, float, float]

#: A generated world: its size [m], and where the robot starts and ends (facing +x).
WORLD_SIZE = (8.0, 5.0)
GENERATED_START: Pose3 = (1.0, 2.5, 0.0)
GENERATED_GOAL: Pose3 = (7.0, 2.5, 0.0)
#: Boxes keep this far from the start and the goal [m]: the robot is never born in a wall.
KEEP_CLEAR = 0.9
#: Redraws of an uncrossable world before giving up (dense worlds are often closed).
MAX_REDRAWS = 50


class ScenarioError(Exception):
    """A scenario that cannot be run, with the reason."""


@dataclass(frozen=True)
class Scenario:
    name: str
    map: Path
    start: Pose3
    goal: Pose3
    #: The shortest collision-free path's length [m] for the robot's inscribed circle (BARN's
    #: optimal path); None where it was not computed.
    optimal_length: float | None = None


def _inscribed_radius() -> float:
    xs, ys = zip(*DEFAULT_FOOTPRINT, strict=True)
    return min(max(xs), -min(xs), max(ys), -min(ys))


def _dilated(blocked: npt.NDArray[np.bool_], cells: int) -> npt.NDArray[np.bool_]:
    """``blocked`` grown by a disc of ``cells`` cells (where the robot's centre cannot be)."""
    out: npt.NDArray[np.bool_] = blocked.copy()
    h, w = blocked.shape
    for dy in range(-cells, cells + 1):
        for dx in range(-cells, cells + 1):
            if dx * dx + dy * dy > cells * cells:
                continue
            src = blocked[max(0, -dy) : h - max(0, dy), max(0, -dx) : w - max(0, dx)]
            out[max(0, dy) : h - max(0, -dy), max(0, dx) : w - max(0, -dx)] |= src
    return out


def shortest_path_length(world: OccupancyMap, start: Pose3, goal: Pose3) -> float | None:
    """The 8-connected grid path's length [m] from start to goal for the robot's inscribed
    circle (None: no path). Unknown cells count as blocked, as Nav2's planners default."""
    res = world.resolution
    blocked = _dilated(world.occupancy != FREE, math.ceil(_inscribed_radius() / res))

    def cell(pose: Pose3) -> tuple[int, int]:
        return (int((pose[1] - world.origin_y) / res), int((pose[0] - world.origin_x) / res))

    source, target = cell(start), cell(goal)
    h, w = blocked.shape
    if not all(0 <= r < h and 0 <= c < w and not blocked[r, c] for r, c in (source, target)):
        return None
    dist = {source: 0.0}
    queue = [(0.0, source)]
    steps = [(dr, dc, math.hypot(dr, dc)) for dr in (-1, 0, 1) for dc in (-1, 0, 1) if dr or dc]
    while queue:
        d, (r, c) = heapq.heappop(queue)
        if (r, c) == target:
            return d * res
        if d > dist[(r, c)]:
            continue
        for dr, dc, step in steps:
            nr, nc = r + dr, c + dc
            if 0 <= nr < h and 0 <= nc < w and not blocked[nr, nc]:
                nd = d + step
                if nd < dist.get((nr, nc), math.inf):
                    dist[(nr, nc)] = nd
                    heapq.heappush(queue, (nd, (nr, nc)))
    return None


def _boxes(seed: int, density: float) -> Canvas:
    """Walls, then random boxes between start and goal until ``density`` of that area is
    occupied."""
    canvas = Canvas(*WORLD_SIZE)
    canvas.walls()
    rng = np.random.default_rng(seed)
    x0, x1 = GENERATED_START[0] + 0.5, GENERATED_GOAL[0] - 0.5
    region = canvas.grid[:, round(x0 / RESOLUTION) : round(x1 / RESOLUTION)]
    target = density * region.size
    for _ in range(10_000):  # bounded: a density the clear discs forbid ends too
        if np.count_nonzero(region == OCCUPIED) >= target:
            break
        x, y = rng.uniform(x0, x1), rng.uniform(0.2, WORLD_SIZE[1] - 0.2)
        w, h = rng.uniform(0.15, 0.5), rng.uniform(0.15, 0.5)
        cx, cy = x + w / 2, y + h / 2
        if any(
            math.hypot(cx - px, cy - py) < KEEP_CLEAR + max(w, h) / 2
            for px, py, _ in (GENERATED_START, GENERATED_GOAL)
        ):
            continue
        canvas.box(x, y, min(x + w, WORLD_SIZE[0] - 0.2), min(y + h, WORLD_SIZE[1] - 0.2))
    return canvas


def generated(index: int, seed: int, density: float, folder: Path) -> Scenario:
    """The ``index``-th generated world of ``seed`` at ``density`` (0..1 of the area between
    start and goal), written to ``folder`` as map_server YAML + PGM."""
    if not 0.0 <= density < 1.0:
        raise ScenarioError(f"--density {density:g}: give a fraction in [0, 1)")
    name = f"gen_s{seed}_d{round(density * 100)}_{index:03d}"
    for redraw in range(MAX_REDRAWS):
        canvas = _boxes(seed * 1_000_003 + index * 1009 + redraw, density)
        world = OccupancyMap(canvas.grid, RESOLUTION, 0.0, 0.0, name)
        length = shortest_path_length(world, GENERATED_START, GENERATED_GOAL)
        if length is not None:
            folder.mkdir(parents=True, exist_ok=True)
            path = folder / f"{name}.yaml"
            save_map(path, canvas.grid, RESOLUTION, (0.0, 0.0), GENERATED_START, GENERATED_GOAL)
            return Scenario(name, path, GENERATED_START, GENERATED_GOAL, length)
    raise ScenarioError(
        f"no crossable world at --density {density:g} in {MAX_REDRAWS} draws: lower it"
    )


def from_map(name_or_path: str, start: Pose3 | None, goal: Pose3 | None) -> Scenario:
    """A bundled map by name or a map_server YAML, its task from the map unless given."""
    path = map_path(name_or_path)
    try:
        world = load_map(path)
    except MapError as exc:
        hint = "" if path.exists() else f" (the bundled maps: {', '.join(BUNDLED)})"
        raise ScenarioError(f"{exc}{hint}") from exc
    start, goal = start or world.start, goal or world.goal
    if start is None or goal is None:
        raise ScenarioError(
            f"{path} has no task (a nav2_pyif: {{start, goal}} block): give --start and --goal"
        )
    return Scenario(path.stem, path, start, goal, shortest_path_length(world, start, goal))
