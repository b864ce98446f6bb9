"""``Costmap.obstacle_points()`` beside the naive version an adapter writes (every cell at or
above the threshold): how long each takes and how many points it hands a DWA, a potential
field or an MPC's constraints, on the bundled maps' inflated global costmaps and on the
controller's 5 m rolling window (the runner's), in-process (no host: the helper's own cost);
and with what a DWA then does with them each cycle: the nearest obstacle to each of 400
candidate poses (20 trajectories x 20 steps), as (400, N) distances.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import numpy as np
from nav2_pyif import Costmap
from nav2_pyif.common.option_types import positive_int
from nav2_pyif.runner.inflation import window
from nav2_pyif.runner.maps import BUNDLED, map_path
from nav2_pyif.runner.run import SimConfig, prepare

from nav2_pyif_bench.stats import Summary, header_row


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--repeats",
        type=positive_int,
        default=200,
        help="calls per costmap and method, >= 1 (default 200)",
    )
    p.add_argument("--quick", action="store_true", help="20 calls per costmap and method")


def naive_points(costmap: Costmap, threshold: int = Costmap.LETHAL) -> np.ndarray:
    """What each adapter wrote before the helper: every lethal cell's centre."""
    hit = (costmap.data >= threshold) & (costmap.data != Costmap.NO_INFORMATION)
    my, mx = np.nonzero(hit)
    return costmap.map_to_world_array(np.stack([mx, my], axis=1))


def _costmaps() -> dict[str, Costmap]:
    out = {}
    for name in BUNDLED:
        result = prepare(SimConfig(map=map_path(name)))
        costmap = result.global_costmap
        out[f"{name}: global ({costmap.size_x} x {costmap.size_y})"] = costmap
        x, y = (result.start[0] + result.goal[0]) / 2, (result.start[1] + result.goal[1]) / 2
        local = window(costmap, x, y, 5.0, 1)
        out[f"{name}: local 5 m window ({local.size_x} x {local.size_y})"] = local
    return out


def _nearest(points: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """The distance [m] from each (x, y) of ``poses`` to its nearest point."""
    d = poses[:, None, :] - points[None, :, :]
    nearest: np.ndarray = np.sqrt((d * d).sum(axis=2)).min(axis=1)
    return nearest


def _candidates(costmap: Costmap) -> np.ndarray:
    """400 poses spread over the costmap's middle: a DWA's rollouts, as points."""
    rng = np.random.default_rng(0)
    w, h = costmap.size_in_meters
    centre = np.array([costmap.origin_x + w / 2, costmap.origin_y + h / 2])
    return centre + rng.uniform(-1.0, 1.0, (400, 2))


def _time(method: Any, repeats: int) -> tuple[Summary, int]:
    samples, points = [], 0
    for _ in range(repeats):
        start = time.perf_counter_ns()
        points = len(method())
        samples.append(time.perf_counter_ns() - start)
    return Summary.of_ns(samples), points


def run(args: argparse.Namespace) -> dict[str, Any]:
    repeats = 20 if args.quick else args.repeats
    rows = {}
    for label, costmap in _costmaps().items():
        poses = _candidates(costmap)
        rows[label] = {
            "obstacle_points() (edges)": _time(costmap.obstacle_points, repeats),
            "every lethal cell (naive)": _time(lambda c=costmap: naive_points(c), repeats),
            "edges + nearest to 400 poses": _time(
                lambda c=costmap, p=poses: _nearest(c.obstacle_points(), p), repeats
            ),
            "naive + nearest to 400 poses": _time(
                lambda c=costmap, p=poses: _nearest(naive_points(c), p), repeats
            ),
        }
    return {"repeats": repeats, "rows": rows}


def report(results: dict[str, Any]) -> str:
    lines = [
        "Costmap.obstacle_points(): edge cells of lethal regions as (N, 2) world points,",
        f"beside every lethal cell ({results['repeats']} calls each, in-process)",
        "",
        header_row(44) + f" {'points':>8}",
    ]
    for label, methods in results["rows"].items():
        lines.append(f"  {label}")
        for method, (summary, points) in methods.items():
            shown = f"{points:>8d}" if "nearest" not in method else f"{'':>8}"
            lines.append(summary.row(f"  {method}", 44) + shown)
    return "\n".join(lines)
