"""``nav2-pyif replay``: a recording's calls to another planner, offline; what changed."""

from __future__ import annotations

import argparse
import contextlib
import logging
import sys
from pathlib import Path

from nav2_pyif.common.option_types import add_path_argument, positive_float
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.recording.format import Recording, read_recording
from nav2_pyif.server.service import PlannerService
from nav2_pyif.server.spec import PlannerSpec

EPILOG = """\
examples:
  # record on the robot (or in a Nav2 launch test), then replay offline
  planner-host --key nav2_pyif/robot1/FollowPath --planner my_pkg.ctrl:MyController \\
      --record out/run.mcap
  nav2-pyif replay out/run.mcap --planner my_pkg.ctrl:MyControllerV2

  # the planners that were recorded, unchanged (a determinism check)
  nav2-pyif replay out/run.mcap

  # a rotated recording, one key only
  nav2-pyif replay out/run*.mcap --serve nav2_pyif/robot1/FollowPath=my_pkg.ctrl:MyController

It writes OUT/NAME.json (a summary and every call: dv, dw, plan distances, compute time,
errors, a digest of each output) and OUT/NAME.png (the differences over time).
"""


def add_replay_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "replay",
        help="replay a recording (planner-host --record) against a planner, offline",
        description="Feed the calls recorded by planner-host --record, in order, to a "
        "planner served as the host serves it (no Nav2, no robot, as fast as it answers), "
        "and report per call how its outputs differ from the recorded ones.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("files", nargs="+", type=Path, metavar="FILE", help="the recording's files")
    p.add_argument(
        "--planner",
        metavar="MODULE:CLASS",
        help="replay every recorded key of this planner's plugin type against it",
    )
    p.add_argument(
        "--serve",
        action="append",
        default=[],
        metavar="PREFIX=MODULE:CLASS",
        help="replay this recorded key against this planner, repeatable",
    )
    p.add_argument(
        "--key",
        action="append",
        default=[],
        metavar="PREFIX",
        help="replay only this key, repeatable (default: the keys --planner / --serve name; "
        "without those, every recorded key against the planner recorded on it)",
    )
    add_path_argument(p)
    p.add_argument(
        "--isolation",
        choices=["process", "none"],
        default="process",
        help="process (default): each planner in a worker process, as planner-host serves "
        "it; none: in this process",
    )
    p.add_argument(
        "--deadline",
        type=positive_float,
        default=60.0,
        metavar="SECONDS",
        help="a call running longer is an error (a hung planner), > 0 (default 60)",
    )
    p.add_argument("--out", type=Path, default=Path("out"), help="output directory")
    p.add_argument("--name", help="output file names (default: FILE's stem + _replay)")
    p.set_defaults(func=run_replay)


def _say(message: str) -> None:
    print(f"nav2-pyif replay: {message}", file=sys.stderr, flush=True)


def choose_specs(args: argparse.Namespace, recording: Recording) -> dict[str, PlannerSpec]:
    """key -> the planner to replay it against. Raises ValueError saying which option is
    wrong, PlannerLoadError when --planner does not load."""
    from nav2_pyif.replay.engine import recorded_spec

    chosen: dict[str, PlannerSpec] = {}
    for item in args.serve:
        key, sep, planner = item.partition("=")
        if not sep:
            raise ValueError(f"--serve {item!r} is not PREFIX=MODULE:CLASS")
        if key not in recording.keys:
            raise ValueError(f"--serve {key}: not recorded (recorded: {_keys(recording)})")
        chosen[key] = PlannerSpec(key, planner)
    if args.planner:
        kind = PlannerSpec("", args.planner).load(quiet=True).plugin_type.value
        matching = [k for k, info in recording.keys.items() if info.plugin_type == kind]
        if not matching:
            raise ValueError(
                f"--planner {args.planner} is a {kind}; the recording has none "
                f"(recorded: {_keys(recording)})"
            )
        for key in matching:
            chosen.setdefault(key, PlannerSpec(key, args.planner))
    if not chosen:
        for key in recording.keys:
            spec = recorded_spec(recording, key)
            if spec is not None:
                chosen[key] = spec
    for key in args.key:
        if key not in chosen:
            raise ValueError(f"--key {key}: no planner to replay it against ({_keys(recording)})")
    return {k: v for k, v in chosen.items() if not args.key or k in args.key}


def _keys(recording: Recording) -> str:
    return ", ".join(f"{k} ({i.plugin_type})" for k, i in recording.keys.items()) or "no key"


def run_replay(args: argparse.Namespace) -> int:
    from nav2_pyif.replay import report
    from nav2_pyif.replay.engine import replay, start

    for path in args.files:
        if not path.is_file():
            _say(f"error: FILE {path}: no such file")
            return 2
    for directory in [str(Path.cwd()), *args.path][::-1]:
        if directory not in sys.path:
            sys.path.insert(0, directory)
    try:
        recording = read_recording(args.files)
    except ImportError:
        _say("error: needs the mcap library: pip install 'nav2-pyif[record]'")
        return 2
    except Exception as exc:  # mcap raises its own errors for a file that is not MCAP
        _say(f"error: cannot read {', '.join(map(str, args.files))}: {exc}")
        return 1
    for path in recording.cut_short:
        _say(f"{path} ends before its index (its host did not end cleanly): read up to there")
    try:
        specs = choose_specs(args, recording)
    except ValueError as exc:
        _say(f"error: {exc}")
        return 2
    except PlannerLoadError as exc:
        _say(f"error: --planner {args.planner}: {exc}")
        return 2
    logging.getLogger("nav2_pyif").setLevel(logging.WARNING)
    services: dict[str, PlannerService] = {}
    with contextlib.ExitStack() as cleanup:
        try:
            for key, spec in specs.items():
                services[key] = start(spec, args.isolation, args.deadline, "WARNING")
                cleanup.callback(services[key].close)
        except PlannerLoadError as exc:
            _say(f"error: {exc}")
            return 2
        try:
            result = replay(recording, services, list(args.files))
        except PlannerLoadError as exc:
            _say(f"error: at a hot swap of the recording: {exc}")
            return 1
    args.out.mkdir(parents=True, exist_ok=True)
    name = args.name or f"{args.files[0].stem}_replay"
    report.write_json(result, args.out / f"{name}.json")
    print(report.table(result))
    written = [args.out / f"{name}.json"]
    try:
        report.plot(result, args.out / f"{name}.png")
        written.append(args.out / f"{name}.png")
    except ImportError:
        _say("no PNG: install the runner extra for plots: pip install 'nav2-pyif[runner]'")
    print(f"wrote {' and '.join(map(str, written))}")
    return 0
