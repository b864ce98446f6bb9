"""The offline runner: plan with a global planner and drive a simulated differential-drive
robot with a controller, both served by a real planner host over Zenoh, through the
reference client: the very protocol and path the Nav2 plugins use."""

from __future__ import annotations

import contextlib
import importlib.machinery
import importlib.util
import logging
import math
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import zenoh
from geometry_msgs.msg import PoseStamped, Twist

from nav2_pyif.client import (
    BehaviorClient,
    ControllerClient,
    GlobalPlannerClient,
    PluginClient,
    Timeouts,
)
from nav2_pyif.client.calls import CallRecord
from nav2_pyif.client.hosts import visible_hosts
from nav2_pyif.common.host_process import PlannerHostProcess, wait_alive
from nav2_pyif.common.reach import open_tool_session
from nav2_pyif.common.signals import Interrupted
from nav2_pyif.common.zenoh_config import ZenohOptions, connect_to
from nav2_pyif.costmap import Costmap
from nav2_pyif.exceptions import Nav2Error
from nav2_pyif.geometry import path_length
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.params import ParamValue
from nav2_pyif.roles import LIFECYCLE_ROLES
from nav2_pyif.runner.aliases import INSTALL_HINT, planner_aliases
from nav2_pyif.runner.extras import KEYS, CycleCalls, LayerEffect, apply_layer, extra_clients
from nav2_pyif.runner.goal_check import GoalCheck
from nav2_pyif.runner.host_log import HostLogFollower
from nav2_pyif.runner.inflation import inflation_layer, static_layer, window
from nav2_pyif.runner.mapfile import MapError, OccupancyMap, load_map
from nav2_pyif.runner.maps import BUNDLED
from nav2_pyif.runner.recovery import Recovery, back_up
from nav2_pyif.runner.robot import DEFAULT_FOOTPRINT, DiffDrive, WorldChecker
from nav2_pyif.runner.sensing import DebugLines, Sensing, SensingConfig, lines_of
from nav2_pyif.runner.swaps import Swap, swaps_during
from nav2_pyif.runner.timing import CycleTiming, cycle_timing

log = logging.getLogger("nav2_pyif.runner")
CONTROLLER_KEY = "nav2_pyif/sim/FollowPath"
#: The outcome of a run the controller's errors ended (its last error ended it mid-cycle).
CONTROLLER_FAILED = "controller failed"
PLANNER_KEY = "nav2_pyif/sim/GridBased"
Pose3 = tuple[float, float, float]
#: The simulated ROS time [s] when a run starts: not zero, which a stamp reads as "no time".
CLOCK_START = 1.0


class SimError(Exception):
    """Bad input for a run (map, poses, planner spec), with the reason."""


class RunInterrupted(Interrupted):
    """A signal ended the run; ``result`` holds what was driven until then."""

    def __init__(self, signum: int, result: SimResult) -> None:
        super().__init__(signum)
        self.result = result


DEFAULTS = {"controller": "pure_pursuit", "planner": "astar"}


@dataclass
class SimConfig:
    map: Path
    # None: the default (DEFAULTS) on a host of our own, whatever a running host serves
    controller: str | None = None
    planner: str | None = None
    start: Pose3 | None = None
    goal: Pose3 | None = None
    rate: float = 20.0  # [Hz] control rate (simulated time)
    timeout: float = 180.0  # [s] simulated time
    # False (lockstep): simulated time advances only once the planner has answered, so the
    # verdict does not depend on the machine's load; each call's time is judged against the
    # control period and call_timeout instead (timing.py). True (real time): a reply later
    # than call_timeout fails its cycle, as on the robot, and the loop keeps wall-clock pace.
    realtime: bool = False
    footprint: tuple[tuple[float, float], ...] = DEFAULT_FOOTPRINT
    inflation_radius: float = 0.55
    cost_scaling_factor: float = 3.0
    local_costmap_size: float = 5.0  # [m] rolling window
    local_costmap_rate: float = 5.0  # [Hz], as Nav2's local costmap update_frequency
    goal_checker: GoalTolerances = field(
        default_factory=lambda: GoalTolerances(0.25, 0.25, 0.25, 0.25)
    )
    stateful_goal_check: bool = True  # SimpleGoalChecker's stateful: the position latches
    failure_tolerance: float = 0.3  # [s] of consecutive controller failures before aborting
    controller_params: dict[str, ParamValue] = field(default_factory=dict)
    planner_params: dict[str, ParamValue] = field(default_factory=dict)
    call_timeout: float = Timeouts().call  # [s] the plugin's timeout (bridge_params.py)
    lockstep_limit: float = 60.0  # [s] lockstep: a call this long is a hung planner
    startup_wait: float = 30.0  # [s] for the host of our own to import and serve the planners
    plan_wait: float = 30.0  # [s] for each create_plan and smooth (the host's plan deadline)
    path: list[str] = field(default_factory=list)  # directories to import planners from
    endpoint: str | None = None  # connect to a running host instead of starting one
    wait: float = 10.0  # [s] with an endpoint: for its router, then for the hosts' tokens
    controller_key: str = CONTROLLER_KEY
    planner_key: str = PLANNER_KEY
    progress: bool = False
    # Nav2's other plugins (extras.KEYS' roles: smoother, goal_checker, progress_checker,
    # layer) -> a reference name or module:Class, and their parameters
    plugins: dict[str, str] = field(default_factory=dict)
    plugin_params: dict[str, dict[str, ParamValue]] = field(default_factory=dict)
    smoother_max_time: float = 1.0  # [s] smoother_server's max_smoothing_duration
    max_recoveries: int = 3  # with a recovery behaviour: how many the run may make
    # runner role ("controller", "planner") -> its module's role -> function map (the
    # plugin's python_delegates), for a planner given as a module of functions
    delegates: dict[str, dict[str, str]] = field(default_factory=dict)
    params_file: Path | None = None  # the Nav2 params file the options came from, if any
    plans: int = 1  # create_plan calls before driving, each timed (the first plan is driven)
    # the simulated laser fed to the controller as input "scan", and the debug outputs kept
    sensing: SensingConfig = field(default_factory=SensingConfig)

    def spec(self, role: str) -> str:
        """The planner asked for as ``role`` ("controller", "planner"), else the default."""
        asked: str | None = getattr(self, role)
        return asked or DEFAULTS[role]


@dataclass
class SimResult:
    config: SimConfig
    world: OccupancyMap
    global_costmap: Costmap
    start: Pose3
    goal: Pose3
    reached: bool = False
    outcome: str = "not started"
    interrupted: str | None = None  # the signal that ended the run early
    served: dict[str, str] = field(default_factory=dict)  # role -> what the host said it serves
    sim_time: float = 0.0
    wall_time: float = 0.0
    plan: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    trajectory: list[tuple[float, float, float, float, float, float]] = field(default_factory=list)
    collisions: int = 0
    min_clearance: float = math.inf
    controller_errors: list[str] = field(default_factory=list)
    traceback: str = ""  # the planner's own traceback of the error that ended the run
    host_log: str = ""  # the log of the planner host the run started (none with an endpoint)
    clock: list[float] = field(default_factory=list)  # unix time each trajectory row's cycle began
    swaps: list[Swap] = field(default_factory=list)  # hot swaps during the run
    records: list[CallRecord] = field(default_factory=list)
    raw_plan: np.ndarray | None = None  # the planner's plan, when a smoother smoothed it
    layer: LayerEffect | None = None  # what the costmap layer changed
    carried: tuple[int, int] = (0, 0)  # checker cycle: calls answered carried / sent alone
    debug: list[DebugLines] = field(default_factory=list)  # the controller's, every few cycles
    scans: int = 0  # simulated scans sent to the controller
    recoveries: list[Recovery] = field(default_factory=list)  # the recovery behaviour's runs
    failed_plans: int = 0  # create_plan calls that raised (of config.plans)

    @property
    def path_length(self) -> float:
        return path_length(self.plan)

    @property
    def driven_distance(self) -> float:
        return path_length([p[1:3] for p in self.trajectory])

    @property
    def cycles(self) -> int:
        return len(self.trajectory)

    @property
    def timing(self) -> CycleTiming:
        """The controller's time per cycle against the control period and the timeout."""
        c = self.config
        return cycle_timing(self.records, c.rate, c.call_timeout, lockstep=not c.realtime)

    def served_over_time(self, role: str) -> list[tuple[float, float, str]]:
        """(from, to [s], short name) of each planner that served ``role``: one span unless
        it was hot-swapped during the run."""
        spans, since, name = [], 0.0, self.name_of(role)
        for swap in self.swaps:
            if swap.role == role:
                spans.append((since, swap.sim_time, name))
                since, name = swap.sim_time, short_name(swap.planner)
        return [*spans, (since, self.sim_time, name)]

    def names_over_time(self, role: str) -> str:
        """``name_of(role)``, or each planner in turn after hot swaps ("a → b")."""
        return " → ".join(name for _, _, name in self.served_over_time(role))

    def name_of(self, role: str) -> str:
        """What drove as ``role`` ("controller", "planner"), by its short name: what the host
        said it serves, else what was asked for."""
        if role in self.served:
            return short_name(self.served[role])
        if role in self.config.plugins:
            return short_name(self.config.plugins[role])
        asked: str | None = getattr(self.config, role)
        return asked or ("unknown" if self.config.endpoint else DEFAULTS[role])


def short_name(spec: str) -> str:
    """A reference planner's alias for its spec or host label, else the spec itself."""
    target = spec.split(" ")[0]  # a host labels a delegates module "module (delegates)"
    return next((alias for alias, t in planner_aliases().items() if t == target), target)


#: The main role (the function-delegate style's) of each role the runner serves.
MAIN_ROLE = {
    "controller": "compute_velocity_commands",
    "planner": "create_plan",
    "smoother": "smooth",
    "goal_checker": "is_goal_reached",
    "progress_checker": "check",
    "layer": "update_costs",
}


def planner_entry(
    key: str,
    spec: str,
    role: str = "controller",
    search: list[str] | None = None,
    delegates: dict[str, str] | None = None,
) -> dict[str, Any]:
    """A host config entry for what serves ``role`` ("controller", "planner", ...): a
    reference alias, ``module:Class``, ``module:function`` (that function as the role's main
    one, the module's others by name) or a module of functions named after the roles (the
    function-delegate style). The host imports it: this process only checks that a module
    named without ``:`` is found on ``search`` (default: sys.path), so a misspelt name is
    refused here with the names the runner knows."""
    aliases = planner_aliases()
    resolved = aliases.get(spec, spec)
    top = resolved.partition(":")[0].split(".")[0]
    module_found = ":" in resolved or (
        top.isidentifier()
        and (
            importlib.machinery.PathFinder.find_spec(top, search or []) is not None
            # sys.path and the meta-path finders (an editable install has its own)
            or importlib.util.find_spec(top) is not None
        )
    )
    if not module_found or resolved.startswith(":") or resolved.endswith(":"):
        known = f"one of {', '.join(aliases)}" if aliases else f"a name of {INSTALL_HINT}"
        raise SimError(
            f"unknown planner {spec!r}: give {known}, "
            "package.module:ClassName, package.module:function, or a module of functions "
            "named after the roles (found in the current directory or with --path)"
        )
    entry: dict[str, Any] = {"key": key}
    if ":" in resolved:
        entry["planner"] = resolved
    else:
        entry["module"] = resolved
    kind_roles = set(delegates or {}) - LIFECYCLE_ROLES
    if delegates and "module" in entry:
        entry["delegates"] = dict(delegates)
    elif kind_roles:  # the lifecycle ones go to whichever planners are modules
        raise SimError(
            f"delegates {', '.join(sorted(kind_roles))} map functions of a module, but the "
            f"{role} is {spec!r}: give a module of functions (--{role} MODULE)"
        )
    if role in MAIN_ROLE:
        entry["kind"] = MAIN_ROLE[role]
    return entry


def import_path(config: SimConfig) -> list[str]:
    """Where the host must look for the run's planners so that it imports them as this process
    would: ``config.path``, then the entry of this process's ``sys.path`` (the caller's
    directory, pytest's rootdir, ...) that holds each planner's top-level package. The host
    is a child process that sees neither on its own."""
    roots = [str(Path(d).resolve()) for d in config.path]
    for spec in (config.spec("controller"), config.spec("planner"), *config.plugins.values()):
        top = spec.partition(":")[0].split(".")[0]
        for entry in sys.path:
            base = Path(entry or ".").resolve()
            if (base / top).is_dir() or (base / f"{top}.py").is_file():
                if str(base) not in roots:
                    roots.append(str(base))
                break
    return roots


def pose_msg(x: float, y: float, yaw: float, frame: str = "map", stamp_s: float = 0.0) -> Any:
    msg = PoseStamped()
    msg.header.frame_id = frame
    msg.header.stamp.sec = int(stamp_s)
    msg.header.stamp.nanosec = int((stamp_s % 1.0) * 1e9)
    msg.pose.position.x, msg.pose.position.y = float(x), float(y)
    msg.pose.orientation.z, msg.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return msg


def prepare(config: SimConfig) -> SimResult:
    """Load and check everything that can be checked before any process starts."""
    try:
        world = load_map(config.map)
    except MapError as exc:
        if config.map.exists():
            raise SimError(str(exc)) from exc
        raise SimError(f"{exc}; the bundled maps: {', '.join(BUNDLED)}") from exc
    start, goal = config.start or world.start, config.goal or world.goal
    if start is None or goal is None:
        raise SimError(f"no start/goal given and {config.map} has no default task")
    footprint = np.array(config.footprint)
    costmap = inflated(config, static_layer(world, footprint=footprint, frame_id="map"))
    checker = WorldChecker(world, footprint)
    for what, (x, y, yaw) in (("start", start), ("goal", goal)):
        if costmap.world_to_map(x, y) is None:
            raise SimError(f"{what} ({x}, {y}) is outside the map")
        if checker.collides(x, y, yaw):
            raise SimError(f"{what} ({x}, {y}) is inside an obstacle")
    return SimResult(config, world, costmap, start, goal)


def inflated(config: SimConfig, master: Costmap) -> Costmap:
    """The master grid after Nav2's inflation layer, for the run's robot."""
    return inflation_layer(
        master, master.inscribed_radius, config.inflation_radius, config.cost_scaling_factor
    )


def run_sim(config: SimConfig) -> SimResult:
    """Run one navigation task; raises SimError for bad input, returns the outcome. A
    terminating signal (``nav2_pyif.common.signals``) stops the run: the host is stopped and
    RunInterrupted carries the result so far."""
    result = prepare(config)
    # where the host will look: --path, the current directory (its own sys.path[0]), ours
    search = [str(Path(d).resolve()) for d in config.path] + [str(Path.cwd())]
    entries = [
        *(
            planner_entry(key, config.spec(role), role, search, config.delegates.get(role))
            for role, key in (
                ("controller", config.controller_key),
                ("planner", config.planner_key),
            )
        ),
        *(planner_entry(KEYS[role], spec, role, search) for role, spec in config.plugins.items()),
    ]
    started = time.perf_counter()
    try:
        with contextlib.ExitStack() as cleanup:
            host = None
            if not config.endpoint:
                # INFO: the planners' self.logger.info lines, shown as they come
                host = PlannerHostProcess(
                    entries,
                    extra_path=import_path(config),
                    log_level="INFO",
                    args=host_deadlines(config),
                    bound=True,  # a killed runner leaves no host behind
                )
                cleanup.callback(host.close)
                host.start()
                follower = HostLogFollower(host.log_path, [e["key"] for e in entries]).start()
                cleanup.callback(_keep_host_log, result, host, follower)
            if config.endpoint:
                # A host already running may be behind a router: be a client, as the C++
                # plugin is, and give a router just started time to listen.
                options = ZenohOptions(
                    connect=[config.endpoint], mode="client", use_environment=False
                )
                session = open_tool_session(options, "nav2-pyif sim", config.wait)
            else:
                session = connect_to([host.endpoint if host else ""], "peer")
            cleanup.callback(session.close)
            _drive(config, result, session, host)
    except Interrupted as exc:
        result.interrupted = exc.name
        result.outcome = f"interrupted by {exc.name}"
        raise RunInterrupted(exc.signum, result) from None
    finally:
        result.wall_time = time.perf_counter() - started
    return result


def host_deadlines(config: SimConfig) -> list[str]:
    """The host's deadlines for a run: create_plan's is the plan wait; in lockstep the call
    deadline is the lockstep limit, so a slow reply is waited for rather than answered
    Unavailable after the host's 1 s."""
    plan = ["--plan-deadline", f"{config.plan_wait:g}"]
    return plan if config.realtime else [*plan, "--deadline", f"{config.lockstep_limit:g}"]


def _drive(
    config: SimConfig, result: SimResult, session: zenoh.Session, host: PlannerHostProcess | None
) -> None:
    start, costmap = result.start, result.global_costmap
    call = config.call_timeout if config.realtime else config.lockstep_limit
    host_wait = 0.0 if config.realtime else config.lockstep_limit  # a lapsed lease is waited out
    timeouts = Timeouts(
        call=call, lifecycle=10.0, configure=60.0, plan=config.plan_wait, host_wait=host_wait
    )
    planner = GlobalPlannerClient(
        session,
        config.planner_key,
        costmap,
        timeouts=timeouts,
        params=config.planner_params,
        record_calls=True,
    )
    local_version = 1
    controller = ControllerClient(
        session,
        config.controller_key,
        window(costmap, start[0], start[1], config.local_costmap_size, local_version),
        timeouts=timeouts,
        params=config.controller_params,
        record_calls=True,
        nav2_params={"controller_frequency": config.rate},  # the control period's source
    )
    extras_started = extra_clients(session, config.plugins, config.plugin_params, costmap, timeouts)
    try:
        with extras_started as extras:
            roles = {"planner": planner, "controller": controller, **extras.clients}
            try:
                _start(config, result, roles, host)
                if extras.layer is not None:  # between the static and the inflation layer
                    static = static_layer(result.world, costmap.footprint, frame_id="map")
                    master, result.layer = apply_layer(extras.layer, static, start)
                    costmap = result.global_costmap = inflated(config, master)
                    planner.update_costmap(costmap)
                    local_version += 1
                    controller.update_costmap(
                        window(
                            costmap, start[0], start[1], config.local_costmap_size, local_version
                        )
                    )
            except _Ended:
                return
            finally:
                result.records = _records(roles)
            _note_served(
                config, result, {"planner": planner.served, "controller": controller.served}
            )
            try:
                try:
                    plan = _create_plans(config, result, planner)
                finally:
                    result.records = _records(roles)
                result.plan = plan.xy_yaw.copy()
                if extras.smoother is not None:
                    result.raw_plan = result.plan
                    plan = extras.smoother.smooth(plan, config.smoother_max_time)
                    result.plan = plan.xy_yaw.copy()
            except Nav2Error as exc:
                _ended_by(result, "no smoothed plan" if len(result.plan) else "no plan", exc)
                return
            try:
                controller.set_plan(plan)
            except Nav2Error as exc:  # Nav2's controller server aborts the goal: a result too
                _ended_by(result, "set_plan failed", exc)
                return
            log.info(
                "plan of %.2f m by %s%s; driving with %s at %g Hz",
                result.path_length,
                result.name_of("planner"),
                f", smoothed by {result.name_of('smoother')}" if extras.smoother else "",
                result.name_of("controller"),
                config.rate,
            )
            calls = CycleCalls(controller, extras, config.goal_checker)
            driving_since = time.time()
            try:
                _control_loop(config, result, calls, local_version)
            finally:
                result.carried = calls.carried
                result.records = _records(roles)
            sim_times = [row[0] for row in result.trajectory]
            result.swaps = swaps_during(session, roles, driving_since, result.clock, sim_times)
            for role, client in reversed(roles.items()):
                try:
                    client.deactivate()
                    client.cleanup()
                except Nav2Error as exc:  # e.g. its worker is restarting after a crash
                    # (said already when it also ended the run)
                    log.log(
                        logging.WARNING if result.reached else logging.DEBUG,
                        "%s: deactivate/cleanup failed: %s",
                        result.name_of(role),
                        exc,
                    )
    finally:
        planner.close()
        controller.close()


def _records(roles: dict[str, PluginClient]) -> list[CallRecord]:
    """Every client's calls, each tagged with its role (the latency table's rows per plugin)."""
    return [replace(r, plugin=role) for role, c in roles.items() for r in c.records or []]


def _create_plans(config: SimConfig, result: SimResult, planner: GlobalPlannerClient) -> Any:
    """``config.plans`` create_plan calls from the start to the goal, each timed in the
    latency table (failed ones in a row of their own): the first plan that came back, else
    the last call's error."""
    bar = _progress_bar(config.progress, config.plans, "plans") if config.plans > 1 else _NoBar()
    first, error = None, None
    try:
        for _ in range(config.plans):
            try:
                plan = planner.create_plan(pose_msg(*result.start), pose_msg(*result.goal))
                first = plan if first is None else first
            except Nav2Error as exc:
                result.failed_plans += 1
                error = exc
            bar.update(1)
    finally:
        bar.close()
    if first is None:
        assert error is not None
        raise error
    if config.plans > 1:
        log.info("%d plans timed (%d failed)", config.plans, result.failed_plans)
    return first


def plan_end(plan: np.ndarray) -> Pose3:
    """The plan's last pose (x, y, yaw): where Nav2's goal checker wants the robot."""
    x, y, yaw = (float(v) for v in plan[-1])
    return x, y, yaw


def _keep_host_log(result: SimResult, host: PlannerHostProcess, follower: HostLogFollower) -> None:
    """The host stopped, its last lines shown, its whole log kept in the result."""
    host.stop()
    follower.stop()
    result.host_log = host.log()


class _Ended(Exception):
    """A plugin could not start: the result says why, and the run stops there."""


def _start(
    config: SimConfig,
    result: SimResult,
    roles: dict[str, PluginClient],
    host: PlannerHostProcess | None,
) -> None:
    """Each client: its host alive, then configure and activate, as Nav2's servers do."""
    started_by = time.monotonic() + config.startup_wait  # for the host of our own
    for role, client in roles.items():
        if host is not None:
            try:
                wait_alive(host, client.wait_for_host, max(0.2, started_by - time.monotonic()))
            except TimeoutError:
                raise TimeoutError(_start_up_timeout(config, result, host)) from None
        elif not client.wait_for_host(config.wait):
            raise SimError(
                f"no planner host on {client.keys.prefix} at {config.endpoint} within "
                f"{config.wait:g} s; {visible_hosts(client.session)}"
            )
        try:
            client.configure()
            client.activate()
        except Nav2Error as exc:
            # As Nav2's server would: the plugin fails to start, so the run stops here.
            what = result.name_of(role)
            _ended_by(result, f"{what} could not start, so the run stopped", exc)
            raise _Ended from exc


def _start_up_timeout(config: SimConfig, result: SimResult, host: PlannerHostProcess) -> str:
    """Why the host of our own did not come up in time: still importing a planner (its
    worker has not said "KEY: loaded"), or serving but not reached."""
    log = host.log()
    loading = [
        result.name_of(role) for role, key in _keys(config).items() if f"{key}: loaded " not in log
    ]
    wait = f"{config.startup_wait:g} s"
    if loading:
        return (
            f"the planner host was still importing {', '.join(loading)} after {wait}: a slow "
            "import (torch, jax, a model's weights) needs a longer start-up wait "
            f"(--startup-wait, or startup_wait in drive()); its log:\n{log}"
        )
    return f"the planner host serves, but was not reached over Zenoh within {wait}:\n{log}"


def _keys(config: SimConfig) -> dict[str, str]:
    """Role -> the key the run's host serves it on."""
    return {
        "controller": config.controller_key,
        "planner": config.planner_key,
        **{role: KEYS[role] for role in config.plugins},
    }


def _ended_by(result: SimResult, what: str, exc: Nav2Error, earlier_traceback: str = "") -> None:
    """The run ends with ``exc``; its traceback is the planner's, else (a call that timed out
    here, say) the latest one an earlier error of the same failure brought."""
    result.outcome = f"{what}: {type(exc).__name__}: {exc}"
    result.traceback = exc.remote_traceback or earlier_traceback


def _note_served(config: SimConfig, result: SimResult, served: dict[str, str | None]) -> None:
    """Record what the host serves; a running host may serve another planner than asked."""
    for role, label in served.items():
        if label is None:
            continue  # a host older than the configure reply's 'planner' field
        result.served[role] = label
        asked: str | None = getattr(config, role)
        if config.endpoint and asked and short_name(asked) != short_name(label):
            log.warning(
                "--%s %s was given, but the host at %s serves %s on %s: the run and its "
                "files are named after what the host serves",
                role,
                asked,
                config.endpoint,
                label,
                getattr(config, f"{role}_key"),
            )


def _advance(
    result: SimResult,
    robot: DiffDrive,
    checker: WorldChecker,
    cmd_v: float,
    cmd_w: float,
    dt: float,
    began: float,
) -> bool:
    """The robot driven by (cmd_v, cmd_w) for ``dt``, recorded; False when it collided (the
    outcome says where)."""
    robot.step(cmd_v, cmd_w, dt)
    result.sim_time += dt
    result.trajectory.append((result.sim_time, robot.x, robot.y, robot.yaw, robot.v, robot.w))
    result.clock.append(began)
    result.min_clearance = min(result.min_clearance, checker.clearance(robot.x, robot.y, robot.yaw))
    if checker.collides(robot.x, robot.y, robot.yaw):
        result.collisions += 1
        result.outcome = f"collision at ({robot.x:.2f}, {robot.y:.2f})"
        return False
    return True


def _recover(
    behavior: BehaviorClient,
    result: SimResult,
    robot: DiffDrive,
    checker: WorldChecker,
    dt: float,
) -> bool:
    """The recovery behaviour's BackUp on the robot; False when the run ends with it (it
    failed, or the robot collided)."""

    def pose_now() -> Any:
        return pose_msg(robot.x, robot.y, robot.yaw, stamp_s=CLOCK_START + result.sim_time)

    def drive(v: float, w: float) -> bool:
        return _advance(result, robot, checker, v, w, dt, time.time())

    what = result.name_of("recovery")
    log.info("t=%.2fs: the controller keeps failing; recovery %s", result.sim_time, what)
    try:
        recovery = back_up(behavior, pose_now, drive, dt, result.sim_time)
    except Nav2Error as exc:
        _ended_by(result, f"the recovery {what} failed", exc)
        return False
    result.recoveries.append(recovery)
    log.info("recovery %s %s after %.1f s", what, recovery.outcome, recovery.seconds)
    if recovery.outcome == "collision":
        return False  # the outcome names the collision
    if recovery.outcome != "succeeded":
        result.outcome = f"{CONTROLLER_FAILED}, and the recovery {what}: {recovery.outcome}"
        return False
    return True


class _NoBar:
    """What the loop calls on a progress bar, doing nothing: no bar is shown."""

    def update(self, n: float) -> None:
        pass

    def set_postfix_str(self, text: str) -> None:
        pass

    def close(self) -> None:
        pass


def _progress_bar(show: bool, total: float, unit: str = "sim s") -> Any:
    """tqdm's bar on stderr when progress is shown, else one that does nothing: tqdm belongs
    to the runner extra (runner/needs.py), so nav2_pyif.testing and the host run without it."""
    if not show:
        return _NoBar()
    from tqdm import tqdm

    if unit != "sim s":
        return tqdm(total=total, unit=unit, desc=f"timing {unit}")
    return tqdm(
        total=round(total, 1),
        unit=unit,
        bar_format="{l_bar}{bar}| {n:.1f}/{total:.0f} sim s [{elapsed}] {postfix}",
    )


def _control_loop(
    config: SimConfig, result: SimResult, calls: CycleCalls, local_version: int
) -> None:
    controller = calls.controller
    # Nav2's controller_server checks the goal on the plan's last pose, not the goal asked for
    end = plan_end(result.plan)
    goal_msg = pose_msg(*end)
    check = GoalCheck(config.goal_checker, end, config.stateful_goal_check)
    calls.start()
    robot = DiffDrive(*result.start)
    checker = WorldChecker(result.world, np.array(config.footprint))
    dt = 1.0 / config.rate
    local_every = max(1, round(config.rate / config.local_costmap_rate))
    sensing = Sensing(config.sensing, result.world, config.rate)
    failing_since: float | None = None
    failure_traceback = ""  # the latest planner traceback since the controller began failing
    bar = _progress_bar(config.progress, config.timeout)
    wall_start = time.perf_counter()
    cycle = 0
    try:
        while result.sim_time < config.timeout:
            if cycle % local_every == 0 and cycle:
                local_version += 1
                controller.update_costmap(
                    window(
                        result.global_costmap,
                        robot.x,
                        robot.y,
                        config.local_costmap_size,
                        local_version,
                    )
                )
            began = time.time()  # when a hot swap happened, in cycles
            velocity = Twist()
            velocity.linear.x, velocity.angular.z = robot.v, robot.w
            stamp_s = CLOCK_START + result.sim_time
            pose = pose_msg(robot.x, robot.y, robot.yaw, stamp_s=stamp_s)
            inputs = sensing.inputs(cycle, stamp_s, robot.x, robot.y, robot.yaw)
            sensed = (inputs, sensing.wanted(cycle, controller.debug_outputs))
            result.scans += len(inputs)
            try:  # the checkers' failures abort the goal in Nav2: no retry
                if calls.goal_reached(pose, goal_msg, velocity, sensed):
                    result.reached = True
                    result.outcome = f"goal reached (said {result.name_of('goal_checker')})"
                    return
                if not calls.making_progress(pose):
                    progress = result.name_of("progress_checker")
                    result.outcome = f"failed to make progress (said {progress})"
                    return
            except Nav2Error as exc:
                _ended_by(result, "a checker failed", exc)
                return
            try:
                cmd = calls.compute(pose, velocity, sensed)
                cmd_v, cmd_w = cmd.twist.linear.x, cmd.twist.angular.z
                failing_since, failure_traceback = None, ""
                for name, msg in controller.debug.items():
                    result.debug.append((result.sim_time, name, lines_of(msg)))
            except Nav2Error as exc:
                result.controller_errors.append(
                    f"t={result.sim_time:.2f}s {type(exc).__name__}: {exc}"
                )
                cmd_v = cmd_w = 0.0  # as Nav2's controller server: stop, then retry
                failing_since = result.sim_time if failing_since is None else failing_since
                failure_traceback = exc.remote_traceback or failure_traceback
                if result.sim_time - failing_since > config.failure_tolerance:
                    recovery = calls.extras.recovery
                    if recovery is None or len(result.recoveries) >= config.max_recoveries:
                        _ended_by(result, CONTROLLER_FAILED, exc, failure_traceback)
                        return
                    if not _recover(recovery, result, robot, checker, dt):
                        return
                    failing_since, failure_traceback = None, ""
                    calls.start()  # a new FollowPath goal: the checkers reset
                    check.xy_reached = False
                    continue
            if not _advance(result, robot, checker, cmd_v, cmd_w, dt, began):
                return
            cycle += 1
            distance = math.hypot(end[0] - robot.x, end[1] - robot.y)
            if calls.cycle is None and check.reached(robot.x, robot.y, robot.yaw):
                result.reached = True
                result.outcome = f"goal reached ({check.passed()})"
                return
            bar.update(dt)
            if cycle % 10 == 0:
                bar.set_postfix_str(f"{distance:.1f} m to goal")
            if config.realtime:
                time.sleep(max(0.0, wall_start + result.sim_time - time.perf_counter()))
        why = (
            "the goal check never passed: "
            + check.why_not(robot.x, robot.y, robot.yaw, result.goal)
            if calls.cycle is None
            else f"{result.name_of('goal_checker')} never said the goal was reached"
        )
        result.outcome = f"timeout after {config.timeout:.0f} s: {why}"
    finally:
        bar.close()
