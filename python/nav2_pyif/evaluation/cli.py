"""``nav2-pyif eval``: planners across many scenarios in one command, compared."""

from __future__ import annotations

import argparse
import itertools
import os
import sys
from pathlib import Path
from typing import Any

from nav2_pyif.common.option_types import (
    add_pose_arguments,
    finite_float,
    non_negative_int,
    positive_float,
    positive_int,
)
from nav2_pyif.evaluation.jobs import PATH_KEY, Entrant, Job, Settings
from nav2_pyif.evaluation.metrics import BARN_MAX_SPEED
from nav2_pyif.evaluation.scenarios import Scenario, ScenarioError, from_map, generated
from nav2_pyif.runner.maps import BUNDLED

EPILOG = f"""\
planners: as nav2-pyif sim's --controller and --planner (a reference name, module:Class,
module:function or a module of functions); every controller runs with every planner.
scenarios: --map (bundled: {", ".join(BUNDLED)}; or a map_server YAML) and --generated N
(random boxes at --density between a start and a goal, from --seed). Without either, the
bundled maps.

examples:
  nav2-pyif eval --controller pure_pursuit apf --generated 10
  nav2-pyif eval --controller pure_pursuit apf mppi --map office cluttered --generated 18
  nav2-pyif eval --controller my_pkg.ctl:Mine --map my_map.yaml --start 1 1 0 --goal 8 4 0
  nav2-pyif eval --controller pure_pursuit --realtime --jobs 1   # wall-clock pace, as a robot
  nav2-pyif eval --compare out/idle out/loaded   # the same report, but for compute figures?

writes (under --out): eval.json (settings, scenarios, the summary and every run), eval.csv
(the summary), eval.png (the summary plotted), scenarios/SCENARIO.png (every planner's path
on the scenario's map), runs/SCENARIO/PLANNER.png and .host.log (each run drawn by the
runner, and its planner host's log), maps/ (the generated maps, map_server YAML + PGM).

lockstep (default): simulated time advances only once the planner has answered, so the
verdicts do not depend on the machine's load; compute per call is measured and reported
against the control period (p99/period). --realtime: the loop keeps wall-clock pace and a
reply later than the plugin's call timeout fails the cycle, as on a robot.
"""


def add_eval_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "eval",
        help="run planners across many scenarios and compare them",
        description="Run one or more planners (controllers and global planners) across "
        "scenarios (bundled, your own and generated maps) in parallel processes, each run "
        "through a planner host over Zenoh, and compare them: success rate, time to goal, "
        "path length, minimum clearance, jerk, compute per call (median, p99) and BARN's "
        "score.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--controller",
        nargs="+",
        default=["pure_pursuit"],
        metavar="SPEC",
        help="controllers to compare (default pure_pursuit)",
    )
    p.add_argument(
        "--planner",
        nargs="+",
        default=["astar"],
        metavar="SPEC",
        help="global planners to compare (default astar)",
    )
    p.add_argument(
        "--map",
        nargs="+",
        default=[],
        metavar="MAP",
        help="bundled map names or map_server YAML paths",
    )
    add_pose_arguments(p, "for --map maps that have no task")
    p.add_argument(
        "--generated",
        type=non_negative_int,
        default=0,
        metavar="N",
        help="N generated scenarios, >= 0 (default 0)",
    )
    p.add_argument(
        "--density",
        type=finite_float,
        default=0.1,
        metavar="FRACTION",
        help="generated maps: fraction of the area between start and goal in "
        "obstacles, in [0, 1) (default 0.1)",
    )
    p.add_argument(
        "--seed", type=non_negative_int, default=0, help="generated maps' seed, >= 0 (default 0)"
    )
    p.add_argument(
        "--rate", type=positive_float, default=20.0, help="control rate [Hz], > 0 (default 20)"
    )
    p.add_argument(
        "--timeout",
        type=positive_float,
        default=120.0,
        metavar="SECONDS",
        help="simulated seconds before a run ends NOT REACHED, > 0 (default 120)",
    )
    p.add_argument(
        "--realtime",
        action="store_true",
        help="pace to wall-clock time with the plugin's call timeout (default: lockstep)",
    )
    p.add_argument(
        "--jobs",
        type=positive_int,
        default=os.cpu_count() or 1,
        metavar="N",
        help="runs at a time, each in a process of its own with its own planner "
        "host, >= 1 (default: the CPU count)",
    )
    p.add_argument(
        "--barn-max-speed",
        type=positive_float,
        default=BARN_MAX_SPEED,
        metavar="M_PER_S",
        help="BARN score: the speed that makes the optimal "
        "time from the optimal path, > 0 "
        f"(default {BARN_MAX_SPEED:g}, BARN's)",
    )
    p.add_argument(
        "--path",
        action="append",
        default=[],
        metavar="DIR",
        help="directory to import planners from, repeatable",
    )
    p.add_argument(
        "--out", type=Path, default=Path("out/eval"), help="output directory (default out/eval)"
    )
    p.add_argument(
        "--compare",
        nargs=2,
        type=Path,
        metavar=("A", "B"),
        help="run nothing: compare two reports (--out directories or eval.json files) "
        "less the compute figures; exit 0 when identical, 1 listing what differs",
    )
    p.add_argument("--no-plots", action="store_true", help="no PNG per scenario and per run")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run_command)


def entrants(controllers: list[str], planners: list[str]) -> list[Entrant]:
    """Every controller with every planner, named by the controller alone when one planner
    is compared."""
    out = []
    for controller, planner in itertools.product(controllers, planners):
        label = controller if len(planners) == 1 else f"{controller}+{planner}"
        out.append(Entrant(controller, planner, label))
    labels = [e.label for e in out]
    if len(set(labels)) != len(labels):
        raise ScenarioError(f"a planner is named twice: {', '.join(labels)}")
    return out


def scenarios(args: argparse.Namespace) -> list[Scenario]:
    start = tuple(args.start) if args.start else None
    goal = tuple(args.goal) if args.goal else None
    names = args.map or ([] if args.generated else list(BUNDLED))
    found = [from_map(name, start, goal) for name in names]  # type: ignore[arg-type]
    folder = args.out / "maps"
    found += [generated(i, args.seed, args.density, folder) for i in range(args.generated)]
    taken = [s.name for s in found]
    if len(set(taken)) != len(taken):
        raise ScenarioError(f"a scenario is named twice: {', '.join(taken)}")
    return found


def run_command(args: argparse.Namespace) -> int:
    from nav2_pyif.evaluation.jobs import run_jobs
    from nav2_pyif.evaluation.report import (
        draw_summary,
        format_table,
        summarize,
        write_csv,
        write_json,
    )
    from nav2_pyif.runner.needs import INSTALL_HINT, missing

    if args.compare:
        from nav2_pyif.evaluation.compare import CompareError, run_compare

        try:
            return run_compare(*args.compare)
        except CompareError as exc:
            print(f"nav2-pyif eval: error: --compare: {exc}", file=sys.stderr)
            return 2
    progress = not args.no_progress and sys.stderr.isatty()
    absent = missing(progress=progress)
    if absent:
        print(f"nav2-pyif eval: needs {' and '.join(absent)}: {INSTALL_HINT}", file=sys.stderr)
        return 1
    try:
        args.out.mkdir(parents=True, exist_ok=True)
        chosen = scenarios(args)
        compared = entrants(args.controller, args.planner)
    except (ScenarioError, OSError) as exc:
        print(f"nav2-pyif eval: error: {exc}", file=sys.stderr)
        return 2
    settings = Settings(
        rate=args.rate,
        timeout=args.timeout,
        realtime=args.realtime,
        path=tuple(str(Path(d).resolve()) for d in args.path),
        draw_to=None if args.no_plots else args.out / "runs",
        barn_max_speed=args.barn_max_speed,
    )
    jobs = [Job(s, e, settings) for s in chosen for e in compared]
    workers = min(args.jobs, len(jobs))
    print(
        f"nav2-pyif eval: {len(compared)} planner(s) x {len(chosen)} scenario(s), "
        f"{'real time' if args.realtime else 'lockstep'}, {workers} at a time",
        file=sys.stderr,
    )
    bar = _bar(progress, len(jobs))
    try:
        rows = run_jobs(jobs, workers, lambda row: bar.update(1))
    finally:
        bar.close()
    paths = [row.pop(PATH_KEY, []) for row in rows]
    if not args.no_plots:
        _draw_scenarios(chosen, rows, paths, args.out / "scenarios")
    labels = [e.label for e in compared]
    summary = summarize(rows, labels)
    report = {
        "settings": {
            "mode": "realtime" if args.realtime else "lockstep",
            "rate_hz": args.rate,
            "timeout_s": args.timeout,
            "barn_max_speed": args.barn_max_speed,
            "workers": workers,
        },
        "scenarios": [_scenario_record(s) for s in chosen],
        "summary": summary,
        "runs": rows,
    }
    write_json(report, args.out / "eval.json")
    write_csv(summary, args.out / "eval.csv")
    draw_summary(summary, len(chosen), args.out / "eval.png")
    print(format_table(summary))
    written = ["eval.json", "eval.csv", "eval.png"]
    written += [] if args.no_plots else ["scenarios/", "runs/"]
    print(f"\nwrote {', '.join(str(args.out / w) for w in written)}")
    return 0


def _draw_scenarios(
    chosen: list[Scenario], rows: list[dict[str, Any]], paths: list[Any], folder: Path
) -> None:
    """A PNG per scenario: every planner's driven path on its map."""
    from nav2_pyif.evaluation.plot import draw_scenario

    folder.mkdir(parents=True, exist_ok=True)
    for scenario in chosen:
        mine = [i for i, row in enumerate(rows) if row["scenario"] == scenario.name]
        driven = {rows[i]["planner"]: paths[i] for i in mine}
        draw_scenario(scenario, [rows[i] for i in mine], driven, folder / f"{scenario.name}.png")


def _scenario_record(s: Scenario) -> dict[str, Any]:
    return {
        "name": s.name,
        "map": s.map.name,
        "start": list(s.start),
        "goal": list(s.goal),
        "optimal_length_m": None if s.optimal_length is None else round(s.optimal_length, 4),
    }


class _NoBar:
    def update(self, n: int) -> None:
        pass

    def close(self) -> None:
        pass


def _bar(show: bool, total: int) -> Any:
    if not show:
        return _NoBar()
    from tqdm import tqdm

    return tqdm(total=total, unit="run", desc="eval")
