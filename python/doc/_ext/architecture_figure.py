"""The call path of one control cycle, drawn with matplotlib (the site's architecture page)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display where the site is built

import matplotlib.pyplot as plt
from matplotlib.patches import FancyBboxPatch

NAV2, NETWORK, PYTHON = "#dde7f5", "#f3f3f3", "#e3f2e1"  # box colours by side
#: (x, y, width, height, title, detail, colour) of each box, in figure units
BOXES = [
    (0.2, 3.2, 2.6, 1.3, "controller_server", "Nav2, C++", NAV2),
    (0.2, 1.2, 2.6, 1.3, "PyController plugin", "C++: encode, query,\ndecode, throw", NAV2),
    (
        3.9,
        1.2,
        2.4,
        1.3,
        "Zenoh",
        "router or peer-to-peer;\nkey nav2_pyif/robot1/FollowPath",
        NETWORK,
    ),
    (7.4, 1.2, 2.6, 1.3, "planner host", "Python: queryable,\nsupervisor, session journal", PYTHON),
    (7.4, 3.2, 2.6, 1.3, "worker process", "your planner:\ncompute_velocity_commands", PYTHON),
]
#: (from, to, label) arrows, as (x, y) points
ARROWS = [
    ((1.5, 3.2), (1.5, 2.5), "computeVelocityCommands"),
    ((2.8, 2.05), (3.9, 2.05), "get (msgpack)"),
    ((6.3, 2.05), (7.4, 2.05), "query"),
    ((8.7, 2.5), (8.7, 3.2), "call"),
    ((7.4, 1.55), (6.3, 1.55), "reply"),
    ((3.9, 1.55), (2.8, 1.55), "TwistStamped\nor error"),
]


def draw_call_path(path: Path) -> None:
    fig, ax = plt.subplots(figsize=(10.2, 4.8), dpi=100)
    ax.set_xlim(0, 10.2)
    ax.set_ylim(0.3, 4.8)
    ax.axis("off")
    for x, y, w, h, title, detail, colour in BOXES:
        ax.add_patch(
            FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.05", fc=colour, ec="#333333")
        )
        ax.text(x + w / 2, y + h - 0.3, title, ha="center", va="center", weight="bold")
        ax.text(x + w / 2, y + 0.45, detail, ha="center", va="center", fontsize=8.5)
    for start, end, label in ARROWS:
        ax.annotate("", end, start, arrowprops={"arrowstyle": "->", "lw": 1.6})
        mx, my = (start[0] + end[0]) / 2, (start[1] + end[1]) / 2
        vertical = start[0] == end[0]
        ax.text(
            mx + (0.1 if vertical else 0),
            my + (0 if vertical else (0.18 if end[0] > start[0] else -0.25)),
            label,
            ha="left" if vertical else "center",
            va="center",
            fontsize=8.5,
        )
    ax.text(
        5.1,
        0.6,
        "A crash, hang or bad answer in the worker becomes a nav2_core exception in the plugin; "
        "the supervisor restarts the worker and restores the session.",
        ha="center",
        fontsize=8.5,
        style="italic",
    )
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
