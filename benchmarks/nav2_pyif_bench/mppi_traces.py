"""Where the MPPI side-by-side's drives spend their time: the traces its harness writes with
$NAV2_PYIF_MPPI_TRACES (a JSON file per stack: every drive's cmd_vel and poses over time),
as a table per drive (time to the goal, to 90 % of the path, the median forward speed over
the middle half) and, with ``--png``, one drive's commands over time, one line per stack."""

from __future__ import annotations

import argparse
import itertools
import json
import math
import statistics
from pathlib import Path
from typing import Any


def load(directory: Path) -> dict[str, list[dict[str, Any]]]:
    """{stack name: its drives} from a traces directory."""
    stacks = {f.stem: json.loads(f.read_text()) for f in sorted(directory.glob("*.json"))}
    if not stacks:
        raise FileNotFoundError(
            f"no traces in {directory}: run the side-by-side with NAV2_PYIF_MPPI_TRACES={directory}"
        )
    return stacks


def summary(drive: dict[str, Any]) -> dict[str, float]:
    """A drive's time to the goal, to 90 % of the path it drove, and its median forward
    speed over the middle half of its commands."""
    poses, commands = drive["poses"], drive["commands"]
    along = [0.0]
    for a, b in itertools.pairwise(poses):
        along.append(along[-1] + math.dist(a[1:], b[1:]))
    t90 = next((p[0] for p, s in zip(poses, along, strict=True) if s >= 0.9 * along[-1]), 0.0)
    vx = [c[1] for c in commands]
    middle = vx[len(vx) // 4 : 3 * len(vx) // 4] or vx or [0.0]
    return {
        "seconds": poses[-1][0] if poses else 0.0,
        "to_90_percent_s": t90,
        "middle_vx": statistics.median(middle),
        "metres": along[-1],
    }


def run(args: argparse.Namespace) -> dict[str, Any]:
    stacks = load(Path(args.directory))
    results = {name: [summary(d) for d in drives] for name, drives in stacks.items()}
    if args.png:
        plot(stacks, args.drive, Path(args.png))
    return {"stacks": results, "drive": args.drive, "png": args.png}


def report(results: dict[str, Any]) -> str:
    header = ("stack", "drive", "to goal", "to 90 %", "middle vx", "path")
    lines = ["{:34s} {:>5s} {:>8s} {:>8s} {:>10s} {:>7s}".format(*header)]
    for name, drives in results["stacks"].items():
        for i, d in enumerate(drives):
            lines.append(
                f"{name:34s} {i:5d} {d['seconds']:7.2f}s {d['to_90_percent_s']:7.2f}s "
                f"{d['middle_vx']:8.3f}m/s {d['metres']:6.2f}m"
            )
    if results["png"]:
        lines.append(f"wrote {results['png']} (drive {results['drive']})")
    return "\n".join(lines)


def plot(stacks: dict[str, list[dict[str, Any]]], drive: int, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.pyplot as plt

    for name, drives in stacks.items():
        if drive >= len(drives):
            raise ValueError(f"{name} has {len(drives)} drives; --drive {drive} is not one")
    fig, (vx, wz) = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True, constrained_layout=True)
    for name, drives in stacks.items():
        commands = drives[drive]["commands"]  # (s, vx, wz) rows; none if no cmd_vel was heard
        t, forward, turn = zip(*commands, strict=True) if commands else ((), (), ())
        vx.plot(t, forward, lw=1, label=name)
        wz.plot(t, turn, lw=1, label=name)
    vx.set(ylabel="cmd_vel vx [m/s]", title=f"drive {drive}: the commands over time")
    wz.set(ylabel="cmd_vel wz [rad/s]", xlabel="seconds since the goal was sent")
    vx.legend(fontsize=7)
    fig.savefig(path, dpi=110)
    plt.close(fig)
