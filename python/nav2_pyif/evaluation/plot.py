"""A scenario's picture in ``nav2-pyif eval``: the map and every planner's driven path on it,
each with its outcome (each run's own picture, with costs and timing, is the runner's)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # files only, no display needed

import matplotlib.pyplot as plt
import numpy as np

from nav2_pyif.evaluation.scenarios import Scenario
from nav2_pyif.runner.mapfile import OCCUPIED, UNKNOWN, load_map


def draw_scenario(
    scenario: Scenario, rows: list[dict[str, Any]], paths: dict[str, Any], path: Path
) -> None:
    """``paths``: planner -> its driven (x, y) points; ``rows``: the runs' report rows."""
    world = load_map(scenario.map)
    extent = (
        world.origin_x,
        world.origin_x + world.size_x * world.resolution,
        world.origin_y,
        world.origin_y + world.size_y * world.resolution,
    )
    shade = np.full(world.occupancy.shape, 1.0)
    shade[world.occupancy == UNKNOWN] = 0.75
    shade[world.occupancy == OCCUPIED] = 0.0
    fig, ax = plt.subplots(figsize=(9, 6), constrained_layout=True)
    ax.imshow(shade, cmap="gray", origin="lower", extent=extent, vmin=0, vmax=1)
    for i, row in enumerate(rows):
        xy = np.asarray(paths.get(row["planner"], []), dtype=float).reshape(-1, 2)
        verdict = "reached" if row.get("success") else row.get("outcome", "")
        time_s = row.get("time_to_goal_s")
        label = f"{row['planner']}: {verdict}" + (f" in {time_s:.1f} s" if time_s else "")
        ax.plot(xy[:, 0], xy[:, 1], color=f"C{i}", lw=1.6, label=label[:70])
    ax.plot(*scenario.start[:2], "o", color="tab:green", ms=9, label="start")
    ax.plot(*scenario.goal[:2], "*", color="tab:red", ms=14, label="goal")
    ax.set_title(scenario.name)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, fontsize=8)
    fig.savefig(path, dpi=100, metadata={"Title": scenario.name})
    plt.close(fig)
