"""The run as a picture: map, inflated costmap, plan, the controller's debug outputs and the
driven trajectory; speed and controller compute time over the run."""

from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # files only, no display needed

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from nav2_pyif.costmap import Costmap
from nav2_pyif.runner.mapfile import OCCUPIED, UNKNOWN
from nav2_pyif.runner.report import clearance_text, summary
from nav2_pyif.runner.run import SimResult, short_name


def draw(result: SimResult, path: Path) -> None:
    """Write the run's picture to ``path`` (PNG); its Title metadata is the map's title."""
    fig = figure(result)
    fig.savefig(path, dpi=110, metadata={"Title": title(result)})
    plt.close(fig)


def title(result: SimResult) -> str:
    s = summary(result)
    controller, planner = result.names_over_time("controller"), result.names_over_time("planner")
    return (
        f"{Path(s['map']).stem}: {controller} + {planner} — "
        f"{'reached' if s['reached'] else s['outcome']} in {s['sim_time_s']:.1f} s, "
        f"{s['driven_distance_m']:.1f} m, min clearance {clearance_text(s['min_clearance_m'], 2)}"
    )


def figure(result: SimResult) -> Figure:
    """The run drawn: the map with costs, plan and trajectory; speeds; latency per cycle."""
    world, costmap = result.world, result.global_costmap
    extent = (
        world.origin_x,
        world.origin_x + world.size_x * world.resolution,
        world.origin_y,
        world.origin_y + world.size_y * world.resolution,
    )
    fig = plt.figure(figsize=(13, 7), constrained_layout=True)  # room for the legend
    grid = fig.add_gridspec(2, 3)
    ax = fig.add_subplot(grid[:, :2])
    base = np.full(world.occupancy.shape, 1.0)
    base[world.occupancy == UNKNOWN] = 0.75
    base[world.occupancy == OCCUPIED] = 0.0
    ax.imshow(base, cmap="gray", origin="lower", extent=extent, vmin=0, vmax=1)
    inflated = np.ma.masked_where(
        (costmap.data == 0) | (costmap.data >= Costmap.LETHAL), costmap.data.astype(float)
    )
    shading = ax.imshow(
        inflated,
        cmap=ListedColormap(plt.cm.magma_r(np.linspace(0.05, 0.7, 64))),
        origin="lower",
        extent=extent,
        alpha=0.45,
        vmin=1,
        vmax=253,
    )
    if result.layer is not None and result.layer.cells.any():
        ax.imshow(
            np.ma.masked_where(~result.layer.cells, np.ones(result.layer.cells.shape)),
            cmap=ListedColormap(["tab:cyan"]),
            origin="lower",
            extent=extent,
            alpha=0.6,
        )
        ax.plot([], [], "s", color="tab:cyan", alpha=0.6, label=f"{result.name_of('layer')} cells")
    planner = "A*" if result.name_of("planner") == "astar" else result.name_of("planner")
    if result.raw_plan is not None and len(result.raw_plan):
        ax.plot(
            result.raw_plan[:, 0],
            result.raw_plan[:, 1],
            "--",
            color="0.35",
            lw=1.0,
            label=f"plan ({planner})",
        )
        planner = f"smoothed by {result.name_of('smoother')}"
    if len(result.plan):
        ax.plot(
            result.plan[:, 0],
            result.plan[:, 1],
            "-",
            color="tab:blue",
            lw=1.5,
            label=f"plan ({planner})",
        )
    _draw_debug(ax, result)
    if result.trajectory:
        t = np.array(result.trajectory)
        ax.plot(t[:, 1], t[:, 2], "-", color="tab:green", lw=1.6, label="driven", zorder=3)
    sx, sy, syaw = result.start
    gx, gy, gyaw = result.goal
    ax.quiver(
        [sx, gx],
        [sy, gy],
        np.cos([syaw, gyaw]),
        np.sin([syaw, gyaw]),
        color=["tab:orange", "tab:red"],
        scale=25,
        width=0.006,
    )
    ax.plot([sx], [sy], "o", color="tab:orange", label="start")
    ax.plot([gx], [gy], "*", color="tab:red", ms=14, label="goal")
    # quiver draws no legend entry of its own: an arrow marker stands for the two arrows
    ax.plot([], [], ls="none", marker=r"$\rightarrow$", ms=14, color="0.3", label="heading")
    if result.collisions and result.trajectory:
        ax.plot(
            [result.trajectory[-1][1]],
            [result.trajectory[-1][2]],
            "X",
            color="red",
            ms=14,
            label="collision",
        )
    _draw_swaps(ax, result)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal")
    # below the map, never over it (a corner of a map may hold the obstacles that matter)
    legend = ax.legend(
        loc="upper center",
        bbox_to_anchor=(0.5, -0.09),
        ncols=4,
        fontsize=8,
        framealpha=0.9,
    )
    for handle in legend.legend_handles:  # faint sampled lines read in full in the legend
        if isinstance(handle, Line2D | LineCollection):
            handle.set_alpha(1.0)
            handle.set_linewidth(max(1.5, float(np.max(handle.get_linewidth()))))
    bar = fig.colorbar(shading, ax=ax, shrink=0.75, pad=0.01)
    bar.set_label("costmap cost (inflation; black: lethal)", fontsize=8)
    bar.ax.tick_params(labelsize=8)
    ax.set_title(_wrapped(title(result), 90), fontsize=10)

    speed = fig.add_subplot(grid[0, 2])
    if result.trajectory:
        t = np.array(result.trajectory)
        speed.plot(t[:, 0], t[:, 4], label="v [m/s]")
        speed.plot(t[:, 0], t[:, 5], label="ω [rad/s]", alpha=0.7)
        for i, swap in enumerate(result.swaps):
            speed.axvline(
                swap.sim_time, color="black", ls=":", lw=1.0, label="hot swap" if i == 0 else None
            )
        speed.legend(fontsize=8)
    speed.set_xlabel("simulated time [s]")
    speed.set_title(_wrapped("commanded motion", 45), fontsize=10)

    latency = fig.add_subplot(grid[1, 2])
    # with a Python goal checker the goal check's query carries the cycle (PROTOCOL.md §15)
    op = "is_goal_reached" if result.carried[0] else "compute_velocity_commands"
    cycles = [r for r in result.records if r.op == op and r.ok]
    if cycles:
        total = np.array([r.total_ns for r in cycles]) / 1e6
        compute = np.array([r.compute_ns for r in cycles]) / 1e6
        latency.plot(total, lw=0.8, label="round trip")
        latency.plot(
            compute, lw=0.8, label="host compute" + (" (goal check)" if result.carried[0] else "")
        )
        period = 1000.0 / result.config.rate
        latency.axhline(period, color="red", ls="--", lw=0.8, label="control period")
        latency.set_yscale("log")
        latency.set_ylim(top=max(12 * period, 2 * float(total.max())))  # room for the legend
        latency.legend(fontsize=8, loc="upper right", ncols=3)
    latency.set_xlabel("control cycle")
    latency.set_ylabel("ms")
    what = "control cycle (one query)" if result.carried[0] else op
    latency.set_title(_wrapped(f"{what} latency", 45), fontsize=10)
    return fig


#: How each debug output is drawn (lines; one-point outputs as dots), by name: strong enough
#: to see beside the plan and the driven path, the sampled ones under them.
_DEBUG_STYLE: dict[str, dict[str, Any]] = {
    "trajectories": {"color": "darkcyan", "lw": 0.5, "alpha": 0.3, "zorder": 1.5},
    "local_plan": {"color": "darkviolet", "lw": 1.0, "alpha": 0.8, "zorder": 2.5},
}
_DEBUG_LINE = {"color": "tab:gray", "lw": 0.8, "alpha": 0.7, "zorder": 2}
_DEBUG_POINT = {
    "color": "magenta",
    "ls": "none",
    "marker": "o",
    "ms": 3.0,
    "mec": "white",
    "mew": 0.4,
    "zorder": 5,
}


def _draw_debug(ax: Any, result: SimResult) -> None:
    """The controller's debug outputs over the run, as RViz shows them: MPPI's sampled
    trajectories and optimal one, pure pursuit's carrot, ... (one legend entry each)."""
    lines: dict[str, list[np.ndarray]] = {}
    for _, name, kept in result.debug:
        lines.setdefault(name, []).extend(kept)
    for name, kept in lines.items():
        label: str | None = f"{name} (debug output)"
        points = [line for line in kept if len(line) == 1]
        if points:
            xy = np.concatenate(points)
            ax.plot(xy[:, 0], xy[:, 1], label=label, **_DEBUG_POINT)
            label = None
        strips = [line for line in kept if len(line) > 1]
        if strips:
            style = _DEBUG_STYLE.get(name, _DEBUG_LINE)
            ax.add_collection(LineCollection(strips, label=label, **style))


def _draw_swaps(ax: Any, result: SimResult) -> None:
    """Where the robot was at each hot swap, and what was swapped in."""
    if not result.swaps or not result.trajectory:
        return
    t = np.array(result.trajectory)
    for i, swap in enumerate(result.swaps):
        row = min(int(np.searchsorted(t[:, 0], swap.sim_time)), len(t) - 1)
        x, y = t[row, 1], t[row, 2]
        ax.plot([x], [y], "D", color="black", ms=7, zorder=6, label="hot swap" if i == 0 else None)
        ax.annotate(
            f"{swap.role} → {short_name(swap.planner)} at {swap.sim_time:.1f} s",
            (x, y),
            xytext=(8, 8),
            textcoords="offset points",
            fontsize=8,
            bbox={"boxstyle": "round", "fc": "white", "alpha": 0.85},
            zorder=6,
        )


def _wrapped(text: str, width: int) -> str:
    """Titles wrap instead of running into the next panel."""
    return "\n".join(textwrap.wrap(text, width))
