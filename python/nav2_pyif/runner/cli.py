"""``nav2-pyif sim``: run a planner on a map without ROS or Nav2, through a planner host."""

from __future__ import annotations

import argparse
import logging
import math
import sys
from pathlib import Path

import numpy as np

from nav2_pyif.common.host_process import HostExited
from nav2_pyif.common.option_types import (
    add_path_argument,
    add_pose_arguments,
    endpoint,
    non_negative_float,
    non_negative_int,
    number,
    positive_float,
    positive_int,
)
from nav2_pyif.costmap import Costmap, Inflation
from nav2_pyif.exceptions import Nav2Error, PlannerLoadError
from nav2_pyif.params import ParamValue
from nav2_pyif.roles import CONTROLLER_ROLES, LIFECYCLE_ROLES, PLANNER_ROLES, parse_delegates
from nav2_pyif.runner.aliases import INSTALL_HINT, planner_aliases
from nav2_pyif.runner.laser import LaserSpec
from nav2_pyif.runner.maps import BUNDLED
from nav2_pyif.runner.nav2_params import AUTO, DEFAULT_FILE, sim_config
from nav2_pyif.runner.run import (
    CONTROLLER_KEY,
    DEFAULTS,
    PLANNER_KEY,
    RunInterrupted,
    SimConfig,
    SimError,
    SimResult,
    run_sim,
)
from nav2_pyif.runner.sensing import SensingConfig


def _reference_planners() -> str:
    aliases = planner_aliases()
    if not aliases:
        return f"  (none installed: {INSTALL_HINT})"
    width = max(map(len, aliases)) + 2
    return "\n".join(
        f"  {name:<{width}}{target}{'' if ':' in target else ' (function delegates)'}"
        for name, target in aliases.items()
    )


EPILOG = f"""\
planners (--controller, --planner) and Nav2's other plugins (--smoother,
--goal-checker, --progress-checker, --layer): a reference one by name, or your
own as package.module:ClassName, package.module:function (that function as the
role's main one: compute_velocity_commands for --controller, create_plan for
--planner, ...) or package.module (its functions named after the roles: the
function-delegate style). The reference ones:
{_reference_planners()}

examples:
  nav2-pyif sim                                     # office map, pure_pursuit + astar
  nav2-pyif sim --map cluttered --controller mppi
  nav2-pyif sim --map my_map.yaml --start 1 1 0 --goal 8 4 1.57 --controller my.mod:Ctl
  nav2-pyif sim --controller my_functions            # compute_velocity_commands(costmap, ...)
  nav2-pyif sim --controller my.mod:steer --planner my.mod:plan --plans 20
  nav2-pyif sim --connect tcp/127.0.0.1:7447        # use a planner host already running
  nav2-pyif sim --controller my.mod:ScanCtl --scan  # a simulated LaserScan as input 'scan'
  nav2-pyif sim --smoother simple_smoother --goal-checker stopped_goal_checker \\
      --progress-checker simple_progress_checker --layer keepout \\
      --layer-param "polygons=[[[4.5, 2.5], [5.5, 2.5], [5.5, 3.5], [4.5, 3.5]]]"
"""


def simulator_facts() -> str:
    """What the simulated Nav2 does that a planner must know, from the runner's own
    defaults (SimConfig), for --help and the docs."""
    d = SimConfig(map=Path("."))
    xs, ys = zip(*d.footprint, strict=True)
    robot = Costmap(
        np.zeros((1, 1), np.uint8),
        1.0,
        footprint=d.footprint,
        inflation=Inflation(d.inflation_radius, d.cost_scaling_factor),
    )
    g, size = d.goal_checker, f"{d.local_costmap_size:g} m"
    lines = [
        "what the simulated Nav2 does (by Nav2's parameter names):",
        f"  robot: differential drive, footprint {max(xs) - min(xs):g} m x "
        f"{max(ys) - min(ys):g} m (inscribed radius {robot.inscribed_radius:g} m,",
        f"    circumscribed {robot.circumscribed_radius:.3f} m)",
        "  global costmap (the planner's): the whole map, static + inflation layers",
        f"    (inflation_radius {d.inflation_radius:g} m, cost_scaling_factor "
        f"{d.cost_scaling_factor:g}: Costmap.inflation); a cell",
        f"    costing less than circumscribed_cost() = {robot.circumscribed_cost()} cannot "
        "touch the robot at any heading",
        f"  controller's costmap: a {size} x {size} rolling window about the robot, updated "
        f"at {d.local_costmap_rate:g} Hz",
        "  control: --rate Hz; the controller's control_period is 1 / --rate (Nav2's",
        "    controller_frequency); lockstep: each cycle waits for the reply, and the report",
        "    counts those over --call-timeout; --realtime: a reply later fails the cycle;",
        f"    failing cycles stop the robot, and {d.failure_tolerance:g} s of them in a row end "
        "the run (failure_tolerance)",
        "  goal check (SimpleGoalChecker, as controller_server makes it on the plan's last",
        f"    pose): within {g.xy_goal_tolerance:g} m of it AND {g.yaw_goal_tolerance:g} rad of "
        "its heading:",
        "    a position-only controller must turn on the spot at the end (or use",
        "    --goal-checker); controllers get these tolerances as goal_checker",
    ]
    return "\n".join(lines) + "\n"


class _HelpFormatter(argparse.RawDescriptionHelpFormatter, argparse.ArgumentDefaultsHelpFormatter):
    """The epilog as written, and every option's default (but flags', and None: an option
    whose help says what happens without it)."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        if action.default in (None, False, [], argparse.SUPPRESS) or "%(default)" in text:
            return text
        return text + " (default: %(default)s)"


#: The runner's options in seconds: SimConfig field -> (the params file's parameter that sets
#: it, if one does; what it is).
SECONDS_OPTIONS = {
    "call_timeout": (
        "timeout",
        "the plugin's timeout per control cycle call: enforced with --realtime, reported "
        "against in lockstep",
    ),
    "lockstep_limit": ("", "in lockstep: a call taking this long is a hung planner"),
    "startup_wait": (
        "",
        "how long the planner host started here may take to import and serve the planners "
        "(a slow import, such as torch's, needs more)",
    ),
    "plan_wait": ("plan_timeout", "how long each create_plan and smooth may take"),
}

#: The runner's flags for Nav2's other plugins (extras.KEYS' roles), what each does.
PLUGIN_FLAGS = {
    "smoother": "smooth the plan before the controller follows it (e.g. simple_smoother)",
    "goal_checker": "the goal checker of every control cycle (e.g. stopped_goal_checker)",
    "progress_checker": "end the run when no progress is made (e.g. simple_progress_checker)",
    "layer": "a costmap layer applied to the costmap before planning (e.g. keepout)",
    "recovery": "the behaviour run when the controller keeps failing, as Nav2's BackUp "
    "recovery (e.g. free_backup)",
}


def add_sim_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "sim",
        help="drive a simulated robot on a map with a Python controller and planner",
        description="Plan with a global planner and drive a simulated differential-drive "
        "robot with a controller, both served by a planner host over Zenoh "
        "(the path Nav2 uses). Writes a PNG and a JSON record.",
        epilog=EPILOG + "\n" + simulator_facts(),
        formatter_class=_HelpFormatter,
    )
    p.add_argument(
        "--map",
        default="office",
        help=f"bundled map name ({', '.join(BUNDLED)}) or a map_server YAML path",
    )
    p.add_argument(
        "--controller",
        help=f"{DEFAULTS['controller']} when not given; with --connect, what the host serves",
    )
    p.add_argument(
        "--planner",
        help=f"{DEFAULTS['planner']} when not given; with --connect, what the host serves",
    )
    add_pose_arguments(p, "default: the map's task")
    p.add_argument(
        "--rate",
        type=positive_float,
        help="control rate [Hz] (controller_frequency), > 0 (default: the params file's, "
        f"else {SimConfig.rate:g})",
    )
    p.add_argument(
        "--timeout",
        type=positive_float,
        default=180.0,
        metavar="SECONDS",
        help="simulated seconds before the run ends NOT REACHED, > 0",
    )
    p.add_argument(
        "--realtime",
        action="store_true",
        help="real time instead of lockstep: a reply later than --call-timeout fails its "
        "cycle, as on the robot, and the run keeps wall-clock pace. Without it (lockstep) "
        "simulated time waits for every reply, so the verdict does not depend on the "
        "machine's load; the report counts the calls Nav2 would have failed",
    )
    for name, (from_file, what) in SECONDS_OPTIONS.items():
        default = getattr(SimConfig, name)
        p.add_argument(
            f"--{name.replace('_', '-')}",
            type=positive_float,
            default=None if from_file else default,
            metavar="SECONDS",
            help=f"{what}, > 0"
            + (f" (default: the params file's {from_file}, else {default:g})" if from_file else ""),
        )
    p.add_argument(
        "--params-file",
        type=Path,
        metavar="FILE",
        help="the Nav2 params file to judge by, as Nav2 reads it: controller_server's "
        "controller_frequency, failure_tolerance and first goal checker's tolerances, its "
        "nav2_pyif controller and planner_server's nav2_pyif planner (python_planner or "
        "python_module, python_delegates, their parameters, timeout and plan_timeout). "
        f"Options given here win (default: ./{DEFAULT_FILE} when present)",
    )
    p.add_argument(
        "--no-params-file",
        action="store_true",
        help=f"read no params file, not even ./{DEFAULT_FILE}",
    )
    p.add_argument(
        "--delegate",
        action="append",
        default=[],
        metavar="ROLE=FUNCTION",
        help="for a --controller or --planner given as a module of functions: which function "
        "plays ROLE (the plugin's python_delegates), repeatable or comma-separated",
    )
    p.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="controller parameter (YAML value), repeatable",
    )
    p.add_argument(
        "--planner-param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="global planner parameter (YAML value), repeatable",
    )
    for role, what in PLUGIN_FLAGS.items():
        flag = role.replace("_", "-")
        p.add_argument(f"--{flag}", metavar="NAME", help=what)
        p.add_argument(
            f"--{flag}-param",
            action="append",
            default=[],
            metavar="NAME=VALUE",
            help=f"parameter of the --{flag} plugin (YAML value), repeatable",
        )
    p.add_argument(
        "--max-recoveries",
        type=non_negative_int,
        default=3,
        metavar="N",
        help="with --recovery: how many recoveries the run may make before the controller's "
        "failure ends it",
    )
    p.add_argument(
        "--plans",
        type=positive_int,
        default=1,
        metavar="N",
        help="call create_plan N times from the start to the goal before driving, each timed "
        "(the latency table's create_plan row: median and p99 of N; failures in a row of "
        "their own), with a progress bar; the first plan is driven",
    )
    p.add_argument(
        "--smoother-max-time",
        type=positive_float,
        default=1.0,
        metavar="SECONDS",
        help="the smoother's time budget (smoother_server's max_smoothing_duration)",
    )
    add_path_argument(p)
    p.add_argument(
        "--connect",
        type=endpoint,
        metavar="ENDPOINT",
        help="use a running planner host (keys nav2_pyif/sim/FollowPath, "
        "nav2_pyif/sim/GridBased, or --controller-key / --planner-key) instead of starting "
        "one, as a Zenoh client of ENDPOINT (the host listening there, or a router); the run "
        "is named after what it serves",
    )
    p.add_argument(
        "--controller-key",
        default=CONTROLLER_KEY,
        metavar="PREFIX",
        help="with --connect: the controller's key",
    )
    p.add_argument(
        "--planner-key",
        default=PLANNER_KEY,
        metavar="PREFIX",
        help="with --connect: the global planner's key",
    )
    p.add_argument(
        "--wait",
        type=non_negative_float,
        default=10.0,
        metavar="SECONDS",
        help="with --connect: how long to wait for a router at ENDPOINT, then for a host on "
        "each key",
    )
    p.add_argument(
        "--scan",
        action="store_true",
        help="simulate a laser scanner on the map and feed it to the controller as input "
        "'scan' (a sensor_msgs/LaserScan, as the plugin's inputs parameter ships a topic)",
    )
    p.add_argument(
        "--scan-beams", type=positive_int, default=360, help="beams over a full turn, >= 1"
    )
    p.add_argument(
        "--scan-range",
        type=number(float, above=LaserSpec.range_min),
        default=8.0,
        help=f"range_max [m], > range_min {LaserSpec.range_min:g}",
    )
    p.add_argument(
        "--scan-noise", type=non_negative_float, default=0.01, help="noise std dev [m], >= 0"
    )
    p.add_argument("--scan-rate", type=positive_float, default=20.0, help="scans per second, > 0")
    p.add_argument(
        "--debug-every",
        type=non_negative_float,
        default=0.5,
        metavar="SECONDS",
        help="ask for the controller's debug outputs (and draw them) every SECONDS of "
        "simulated time; 0: never",
    )
    p.add_argument("--out", type=Path, default=Path("out"), help="output directory")
    p.add_argument(
        "--name",
        help="file name stem; without it MAP_CONTROLLER, then the planner when not astar "
        "and each other plugin (runs with different planners do not overwrite each other)",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run_command)


def sensing_config(args: argparse.Namespace) -> SensingConfig:
    """The --scan* and --debug-every flags: ``--scan-beams`` evenly over a full turn."""
    try:
        beams = args.scan_beams
        laser = LaserSpec(
            beams=beams,
            angle_max=math.pi * (1 - 2 / beams) if beams > 1 else -math.pi,
            range_max=args.scan_range,
            noise=args.scan_noise,
        )
        return SensingConfig(laser if args.scan else None, args.scan_rate, args.debug_every)
    except ValueError as exc:
        raise SimError(f"--scan-*/--debug-every: {exc}") from exc


def _params(items: list[str], option: str) -> dict[str, ParamValue]:
    """``option``'s NAME=VALUE items, each value read as YAML; bad ones are usage errors."""
    import yaml

    out: dict[str, ParamValue] = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep:
            raise SimError(f"{option} {item!r} is not NAME=VALUE")
        try:
            parsed = yaml.safe_load(value)
        except yaml.YAMLError as exc:
            reason = " ".join(str(getattr(exc, "problem", "") or exc).split())
            raise SimError(f"{option} {item!r}: the value is not YAML ({reason})") from None
        # A parameter is a scalar or an array of scalars; nested lists (polygons, footprints)
        # are written as text, as Nav2's YAML writes footprints
        nested = isinstance(parsed, list) and any(isinstance(v, list | dict) for v in parsed)
        out[name] = value.strip() if nested or isinstance(parsed, dict) else parsed
    return out


def _delegates(items: list[str]) -> dict[str, dict[str, str]] | None:
    """--delegate's ROLE=FUNCTION items, as the controller's and the planner's (their
    lifecycle roles to both: a planner that is no module of functions ignores them)."""
    if not items:
        return None
    try:
        delegates = parse_delegates(items)
    except PlannerLoadError as exc:
        raise SimError(f"--delegate: {exc}") from None
    mine = {
        "controller": CONTROLLER_ROLES | LIFECYCLE_ROLES,
        "planner": PLANNER_ROLES | LIFECYCLE_ROLES,
    }
    out = {role: {r: f for r, f in delegates.items() if r in roles} for role, roles in mine.items()}
    others = set(delegates) - CONTROLLER_ROLES - PLANNER_ROLES - LIFECYCLE_ROLES
    if others:
        raise SimError(
            f"--delegate {', '.join(sorted(others))}: sim maps the controller's and the planner's "
            "roles; the other plugins are given as module:Class or module:function"
        )
    return {role: roles for role, roles in out.items() if roles}


def run_command(args: argparse.Namespace) -> int:
    logging.getLogger("nav2_pyif.runner").setLevel(logging.INFO)  # what runs, on stderr
    from nav2_pyif.runner.maps import map_path
    from nav2_pyif.runner.needs import INSTALL_HINT, missing
    from nav2_pyif.runner.report import format_report

    progress = not args.no_progress and sys.stderr.isatty()
    absent = missing(progress=progress)
    if absent:  # found now, not after a run whose picture could not be drawn
        print(f"nav2-pyif sim: needs {' and '.join(absent)}: {INSTALL_HINT}", file=sys.stderr)
        return 1
    try:
        config = sim_config(
            map_path(args.map),
            None if args.no_params_file else args.params_file or AUTO,
            controller=args.controller,
            planner=args.planner,
            start=tuple(args.start) if args.start else None,
            goal=tuple(args.goal) if args.goal else None,
            rate=args.rate,
            timeout=args.timeout,
            realtime=args.realtime,
            call_timeout=args.call_timeout,
            lockstep_limit=args.lockstep_limit,
            startup_wait=args.startup_wait,
            plan_wait=args.plan_wait,
            controller_params=_params(args.param, "--param") or None,
            planner_params=_params(args.planner_param, "--planner-param") or None,
            delegates=_delegates(args.delegate),
            endpoint=args.connect,
            wait=args.wait,
            controller_key=args.controller_key,
            planner_key=args.planner_key,
            path=args.path or None,
            progress=progress,
            plugins={r: getattr(args, r) for r in PLUGIN_FLAGS if getattr(args, r)},
            plugin_params={
                r: _params(getattr(args, f"{r}_param"), f"--{r.replace('_', '-')}-param")
                for r in PLUGIN_FLAGS
            },
            smoother_max_time=args.smoother_max_time,
            max_recoveries=args.max_recoveries,
            plans=args.plans,
            sensing=sensing_config(args),
        )
        result = run_sim(config)
    except RunInterrupted as exc:
        png, record = _write(exc.result, args)
        print(
            f"nav2-pyif sim: {exc.result.outcome}; wrote the run so far to {png} and {record}",
            file=sys.stderr,
        )
        return exc.exit_code
    except SimError as exc:  # bad input: the usage error's code
        print(f"nav2-pyif sim: error: {exc}", file=sys.stderr)
        return 2
    except (RuntimeError, TimeoutError, ConnectionError, Nav2Error) as exc:  # the run failed
        print(f"nav2-pyif sim: error: {exc}", file=sys.stderr)
        return 2 if isinstance(exc, HostExited) and exc.exit_code == 2 else 1
    png, record = _write(result, args)
    print(format_report(result))
    log_file = f", {png.with_suffix('.host.log')}" if result.host_log else ""
    print(f"\nwrote {png}{log_file} and {record}")
    return 0 if result.reached else 1


def default_stem(result: SimResult) -> str:
    """MAP_CONTROLLER, then a planner other than the default and each other plugin: runs
    with different planners write different files (office_pure_pursuit for the default)."""
    parts = [Path(str(result.config.map)).stem, result.name_of("controller")]
    if result.name_of("planner") != DEFAULTS["planner"]:
        parts.append(result.name_of("planner"))
    parts += [result.name_of(role) for role in result.config.plugins]
    return "_".join(parts).replace(":", ".")


def _write(result: SimResult, args: argparse.Namespace) -> tuple[Path, Path]:
    """The run's PNG and JSON record under --out."""
    from nav2_pyif.runner.plot import draw
    from nav2_pyif.runner.report import write_json

    args.out.mkdir(parents=True, exist_ok=True)
    stem = args.name or default_stem(result)
    png, record = args.out / f"{stem}.png", args.out / f"{stem}.json"
    draw(result, png)
    write_json(result, record)
    if result.host_log:  # the host's own account (where a planner crashed or hung)
        (args.out / f"{stem}.host.log").write_text(result.host_log)
    return png, record
