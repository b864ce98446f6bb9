"""A Python costmap layer's cost per costmap update: the reference keep-out layer
on a 400 x 400 master grid (20 m at 5 cm), through a planner host (worker process), as
nav2_pyif's C++ layer plugin calls it every update: update_bounds, then update_costs for the
window, whose uint8 costs are all that crosses the wire. Paced at 5 Hz (a costmap's usual
update rate, 200 ms budget per update), for the whole grid and for a 3 m x 3 m window.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import numpy as np
from nav2_pyif import Costmap, LayerWindow
from nav2_pyif.client import CostmapLayerClient, Timeouts
from nav2_pyif.common.host_process import PlannerHostProcess
from nav2_pyif.common.option_types import positive_int

from nav2_pyif_bench.protocol_bench import open_session, progress
from nav2_pyif_bench.stats import Summary, header_row

KEY = "bench/robot/keepout"
SIZE, RESOLUTION, ORIGIN = 400, 0.05, -10.0
# a dozen keep-out zones spread over the grid
POLYGONS = str(
    [
        [[x, y], [x + 1.5, y], [x + 1.5, y + 0.8], [x, y + 2.0]]
        for x in (-8.0, -3.0, 2.0, 6.0)
        for y in (-7.0, -1.0, 5.0)
    ]
)
ROWS = {"400 x 400 window (whole grid)": 400, "60 x 60 window (3 m x 3 m)": 60}


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--updates",
        type=positive_int,
        default=100,
        help="updates per window size, at 5 Hz, >= 1 (default 100)",
    )
    p.add_argument("--quick", action="store_true", help="20 updates per window size")


def run(args: argparse.Namespace) -> dict[str, Any]:
    updates = 20 if args.quick else args.updates
    planner = "nav2_pyif_planners.keepout_layer:KeepOutLayer"
    with PlannerHostProcess([{"key": KEY, "planner": planner}]) as host:
        session = open_session([host.endpoint])
        try:
            return _measure(session, updates)
        finally:
            session.close()


def _measure(session: Any, updates: int) -> dict[str, Any]:
    empty = Costmap(np.zeros((0, 0), np.uint8), 1.0, frame_id="map")
    timeouts = Timeouts(call=2.0, lifecycle=5.0, configure=30.0)
    client = CostmapLayerClient(
        session, KEY, empty, params={"polygons": POLYGONS}, timeouts=timeouts
    )
    assert client.wait_for_host(30), f"no planner host on {KEY}"
    client.configure()
    client.activate()
    client.match_size(SIZE, SIZE, RESOLUTION, ORIGIN, ORIGIN)
    rows: dict[str, Any] = {}
    lethal = 0
    for label, cells in ROWS.items():
        first = (SIZE - cells) // 2
        window = LayerWindow(first, first, first + cells, first + cells, ORIGIN, ORIGIN, RESOLUTION)
        progress(f"{updates} updates of a {cells} x {cells} window at 5 Hz")
        samples: list[int] = []
        next_at = time.monotonic()
        for i in range(updates + 5):
            next_at += 0.2
            start = time.perf_counter_ns()
            client.update_bounds((0.0, 0.0, 0.0), (1e30, 1e30, -1e30, -1e30))
            costs, _ = client.update_costs(window)
            if i >= 5:
                samples.append(time.perf_counter_ns() - start)
            lethal = max(lethal, int((costs == 254).sum()))
            time.sleep(max(0.0, next_at - time.monotonic()))
        rows[label] = vars(Summary.of_ns(samples)) | {"bytes": cells * cells}
    return {"updates": updates, "rows": rows, "lethal_cells": lethal}


def report(results: dict[str, Any]) -> str:
    lines = [
        "keep-out layer on a 400 x 400 master at 5 Hz: update_bounds + update_costs",
        header_row(44) + f" {'reply B':>9}",
    ]
    for label, row in results["rows"].items():
        summary = Summary(row["n"], row["median_us"], row["p99_us"], row["mean_us"])
        lines.append(summary.row(label, 44) + f" {row['bytes']:>9d}")
    whole = results["rows"][next(iter(ROWS))]
    lines.append(
        f"  whole grid: {whole['p99_us'] / 2000:.1f} % of the 200 ms update period at p99 "
        f"({results['lethal_cells']} lethal cells in the window)"
    )
    return "\n".join(lines)
