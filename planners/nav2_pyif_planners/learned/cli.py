"""``nav2-pyif learn``: collect, train, save, drive (see pipeline). ``nav2-pyif`` hands this
command its arguments by import path (nav2_pyif never imports the reference planners)."""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

from nav2_pyif.common.option_types import positive_int

from nav2_pyif_planners.learned.policy import default_weights


def parser(prog: str = "nav2-pyif learn") -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog=prog,
        description="Drive the reference MPPI in the offline runner on the bundled maps with "
        "a simulated laser, record (scan, plan window, velocity) -> command, train a small "
        "policy with JAX on JAX's default device, save its weights and drive the --evaluate "
        "map with the learned controller (a PNG and a JSON in --out). Serve it afterwards "
        "with: nav2-pyif sim --controller learned --scan, or in Nav2 with planner-host "
        "--planner nav2_pyif_planners.learned.controller:LearnedController and a LaserScan "
        "topic in the plugin's inputs parameter named 'scan'.",
    )
    p.add_argument(
        "--maps",
        nargs="+",
        default=["office", "cluttered"],
        metavar="MAP",
        help="maps to record demonstrations on (default: office cluttered)",
    )
    p.add_argument(
        "--runs", type=positive_int, default=2, help="demonstrations per map, >= 1 (default 2)"
    )
    p.add_argument(
        "--steps", type=positive_int, default=3000, help="training steps, >= 1 (default 3000)"
    )
    p.add_argument(
        "--weights", type=Path, default=None, help=f"where to save (default {default_weights()})"
    )
    p.add_argument("--evaluate", default="office", metavar="MAP", help="map to drive after")
    p.add_argument("--out", type=Path, default=Path("out"), help="where the drive's PNG goes")
    p.add_argument("--no-progress", action="store_true", help="no progress bars on stderr")
    return p


def main(argv: list[str] | None = None, prog: str = "nav2-pyif learn") -> int:
    from nav2_pyif.runner.plot import draw
    from nav2_pyif.runner.report import write_json
    from nav2_pyif.runner.run import SimError

    from nav2_pyif_planners.learned.pipeline import LearnConfig, Task, learn

    args = parser(prog).parse_args(argv)
    logging.basicConfig(format="[%(levelname)s] [%(name)s] %(message)s")
    logging.getLogger("nav2_pyif").setLevel(logging.INFO)  # what runs, on stderr
    config = LearnConfig(
        tasks=[Task(m) for m in args.maps],
        runs=args.runs,
        steps=args.steps,
        weights=args.weights or default_weights(),
        evaluate=Task(args.evaluate),
        progress=not args.no_progress and sys.stderr.isatty(),
    )
    try:
        result = learn(config)
    except (RuntimeError, ValueError, ImportError, SimError) as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 2
    assert result.drive is not None
    args.out.mkdir(parents=True, exist_ok=True)
    png, record = (
        args.out / f"{args.evaluate}_learned.png",
        args.out / f"{args.evaluate}_learned.json",
    )
    draw(result.drive, png)
    write_json(result.drive, record)
    t = result.training
    print(
        f"{t.samples} samples from {len(result.demonstrations)} demonstrations; trained "
        f"{t.steps} steps in {t.seconds:.1f} s on {t.device} (loss {t.loss:.4f}); "
        f"weights: {result.weights}\n"
        f"learned controller on {args.evaluate}: {result.drive.outcome} "
        f"({result.drive.sim_time:.1f} s simulated); wrote {png} and {record}"
    )
    return 0 if result.drive.reached else 1


if __name__ == "__main__":
    sys.exit(main(prog="python -m nav2_pyif_planners.learned.cli"))
