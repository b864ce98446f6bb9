"""``planner-host``: serve Python planners to Nav2 over Zenoh."""

from __future__ import annotations

import argparse
import faulthandler
import logging
import os
import signal
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from types import FrameType
from typing import Any

import yaml
import zenoh
from nav2_pyif_protocol.keys import validate_prefix

from nav2_pyif._ros_types import check_serialization_rmw
from nav2_pyif.common.env_defaults import apply_environment, document_environment
from nav2_pyif.common.option_types import (
    non_negative_float,
    non_negative_int,
    positive_float,
    positive_int,
)
from nav2_pyif.common.signals import TERMINATING, exit_code
from nav2_pyif.common.zenoh_config import (
    add_zenoh_arguments,
    configured_endpoints,
    open_session,
    options_from_args,
)
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.roles import KIND_ROLES, check_roles, parse_delegates
from nav2_pyif.server.batch_groups import add_batch_arguments, check_batch_arguments, start_all
from nav2_pyif.server.heap import settle_heap
from nav2_pyif.server.host import PlannerHost, ReachWatch, new_host_id
from nav2_pyif.server.loader import PLUGIN_BASES_TEXT
from nav2_pyif.server.parent import bind_to_parent, remove_when_orphaned
from nav2_pyif.server.pid_file import remove_pid_file, write_pid_file
from nav2_pyif.server.recording.options import (
    add_record_arguments,
    check_record_arguments,
    start_live_tap,
    start_recording,
)
from nav2_pyif.server.reload_policy import ReloadPolicy
from nav2_pyif.server.respawn import keep
from nav2_pyif.server.service import InProcessPlanner, PlannerService
from nav2_pyif.server.spec import PlannerSpec
from nav2_pyif.server.supervisor import Deadlines, SupervisedPlanner
from nav2_pyif.server.watch import SourceWatcher, source_roots, watchfiles_missing
from nav2_pyif.server.xla_threads import add_xla_threads_argument, apply_xla_threads

EPILOG = """\
examples:
  # a controller class, on the key the Nav2 params YAML names
  planner-host --key nav2_pyif/robot1/FollowPath --planner my_pkg.ctrl:MyController

  # the function-delegate style: a module and a role -> function map
  planner-host --key nav2_pyif/robot1/FollowPath --module my_pkg.apf \\
      --delegate compute_velocity_commands=compute,set_plan=set_plan

  # ... or functions named after the roles (compute_velocity_commands, set_plan, ...)
  planner-host --key nav2_pyif/robot1/FollowPath --module my_pkg.apf

  # ... or one named after its main role, the others beside it by name
  planner-host --key nav2_pyif/robot1/FollowPath \\
      --planner my_pkg.apf:compute_velocity_commands

  # several planners on one host, no Zenoh router: plugins connect to this host
  planner-host --listen tcp/127.0.0.1:7447 \\
      --serve nav2_pyif/robot1/FollowPath=my_pkg.ctrl:MyController \\
      --serve nav2_pyif/robot1/GridBased=my_pkg.astar:AStar

  # from a YAML file: planners: [{key: K, planner: M:C}, {key: K, module: M, delegates: {..}}]
  # ({key: K, planner: M:function, kind: compute_velocity_commands}: a function as that role)
  planner-host --config planners.yaml

  # one worker for a fleet's controllers, their control cycles batched (window 5 ms)
  planner-host --batch --batch-window 5 \\
      --serve nav2_pyif/robot1/FollowPath=nav2_pyif_planners.mppi_jax:MPPIJax \\
      --serve nav2_pyif/robot2/FollowPath=nav2_pyif_planners.mppi_jax:MPPIJax

  # accept nav2-pyif reload from the network, to the served planners or my_planners.*
  planner-host --key nav2_pyif/robot1/FollowPath --planner my_planners.a:A \\
      --allow-remote-reload --reload-allow 'my_planners.*'

  # started again whenever it exits (as the Nav2 plugin runs the host it starts itself)
  planner-host --respawn --key nav2_pyif/robot1/FollowPath --module my_pkg.apf

  # record every call to MCAP files (replay: nav2-pyif replay run.mcap --planner ...)
  planner-host --key nav2_pyif/robot1/FollowPath --planner my_pkg.ctrl:MyController \\
      --record out/run.mcap

  # every option also reads NAV2_PYIF_<OPTION> (containers); command-line flags win
  NAV2_PYIF_KEY=nav2_pyif/robot1/FollowPath NAV2_PYIF_PLANNER=my_pkg.ctrl:MyController \\
      NAV2_PYIF_CONNECT=tcp/router:7447 planner-host

signals (to this host only: --pid-file FILE, then kill -HUP "$(cat FILE)"):
  SIGHUP          re-import every planner (fresh workers; sessions carry over)
  SIGINT, SIGTERM stop: workers and the Zenoh session are closed, exit code 130 / 143
                  (SIGHUP before the host serves stops it too: 129)
"""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="planner-host",
        description="Serve Python motion planners to Nav2 (nav2_pyif plugins) over Zenoh.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    what = parser.add_argument_group("what to serve")
    what.add_argument(
        "--key", metavar="PREFIX", help="key prefix of the plugin, as in the Nav2 params YAML"
    )
    what.add_argument(
        "--planner",
        metavar="MODULE:CLASS",
        help=f"a {PLUGIN_BASES_TEXT} subclass, e.g. my_pkg.ctrl:MyController; or "
        "MODULE:FUNCTION named after its main role (e.g. my_pkg.apf:compute_velocity_commands)",
    )
    what.add_argument(
        "--module", metavar="MODULE", help="module of plain functions (the plugin's python_module)"
    )
    what.add_argument(
        "--delegate",
        action="append",
        default=[],
        metavar="ROLE=FUNCTION",
        help="role -> function of --module (the plugin's python_delegates), repeatable "
        "or comma-separated; a bare ROLE binds the function of its name; without it, the "
        "functions named after the roles",
    )
    what.add_argument(
        "--serve",
        action="append",
        default=[],
        metavar="PREFIX=MODULE:CLASS",
        help="serve another planner on another key, repeatable",
    )
    what.add_argument(
        "--config",
        type=Path,
        metavar="YAML",
        help="YAML file with a 'planners' list of {key, planner | module+delegates, batch?}",
    )
    what.add_argument(
        "--path",
        action="append",
        default=[],
        metavar="DIR",
        help="directory to import planners from, repeatable (the current "
        "directory is always searched, as with python -m)",
    )
    safety = parser.add_argument_group("isolation")
    safety.add_argument(
        "--isolation",
        choices=["process", "none"],
        default="process",
        help="process (default): each planner in a supervised worker process, restarted with "
        "its sessions when it dies; none: in the host process (lowest latency; a crash takes "
        "the host down)",
    )
    safety.add_argument(
        "--deadline",
        type=positive_float,
        default=1.0,
        metavar="SECONDS",
        help="control-loop calls running longer are answered Unavailable, which the plugin "
        "throws as NoValidControl, > 0 (default 1.0)",
    )
    safety.add_argument(
        "--plan-deadline",
        type=positive_float,
        default=30.0,
        metavar="SECONDS",
        help="the same for create_plan and smooth, > 0 (default 30)",
    )
    safety.add_argument(
        "--hang-grace",
        type=non_negative_float,
        default=3.0,
        metavar="SECONDS",
        help="a worker still busy this long after a deadline is killed and restarted, >= 0 "
        "(default 3.0)",
    )
    safety.add_argument(
        "--memory-limit",
        type=non_negative_int,
        default=0,
        metavar="MB",
        help="address-space limit of each worker process, >= 0; a planner exceeding it gets "
        "MemoryError (default 0: none; GPU frameworks reserve large address spaces)",
    )
    add_xla_threads_argument(safety)
    add_batch_arguments(parser)
    add_record_arguments(parser)
    swap = parser.add_argument_group("hot swap from the network (nav2-pyif reload)")
    swap.add_argument(
        "--allow-remote-reload",
        action="store_true",
        help="accept reload requests over Zenoh (default: refused; SIGHUP always reloads); "
        "without --reload-allow only a fresh import of the planner a key serves",
    )
    swap.add_argument(
        "--reload-allow",
        action="append",
        default=[],
        metavar="PATTERN",
        help="another planner a reload may load: fnmatch pattern on MODULE:CLASS or MODULE, "
        "e.g. 'my_planners.*', repeatable",
    )
    parser.add_argument(
        "--watch",
        action="store_true",
        help="reload a planner when its source files change (its top-level package, or its "
        "module file), as a hot swap: a version that fails to import or configure is refused "
        "and the old one keeps serving (needs the watchfiles library: the 'watch' extra)",
    )
    add_zenoh_arguments(parser)
    parser.add_argument(
        "--pid-file",
        type=Path,
        metavar="FILE",
        help="write the host's process id to FILE once it serves, for a signal sent to this "
        'host only (kill -HUP "$(cat FILE)": reload every planner); removed on exit',
    )
    parser.add_argument(
        "--respawn",
        action="store_true",
        help="keep the host running: serve from a child process started again whenever it "
        "exits (after 1 s, doubling to 30 s; 1 s again after a run of 10 s); SIGINT or SIGTERM "
        "stop both (the child gets SIGTERM, SIGKILL 5 s later). The Nav2 plugin starts its "
        "local host so",
    )
    parser.add_argument(
        "--parent-pid",
        type=positive_int,
        metavar="PID",
        help="the process that starts this host (the Nav2 plugin, nav2-pyif sim): the host "
        "gets SIGTERM when it dies, even by SIGKILL, and starts nothing if it is gone already "
        "(Linux); with --respawn, the keeper does",
    )
    parser.add_argument(
        "--parent-tmpdir",
        type=Path,
        metavar="DIR",
        help="with --parent-pid: the parent's temporary directory (this host's config and log), "
        "removed when the host ends after its parent died",
    )
    parser.add_argument(
        "--log-level",
        default="INFO",
        choices=["DEBUG", "INFO", "WARNING", "ERROR"],
        help="default INFO",
    )
    document_environment(parser)
    return parser


def without_respawn(argv: list[str]) -> list[str]:
    """``argv`` less ``--respawn`` (or an abbreviation argparse took for it)."""
    return [a for a in argv if not (a.startswith("--res") and "--respawn".startswith(a))]


def collect_specs(args: argparse.Namespace, parser: argparse.ArgumentParser) -> list[PlannerSpec]:
    specs: list[PlannerSpec] = []
    if args.planner or args.module:
        if not args.key:
            parser.error("--planner/--module need --key PREFIX")
        if args.planner and args.module:
            parser.error("give either --planner or --module, not both")
        delegates = parse_delegates(args.delegate) if args.module else None
        specs.append(PlannerSpec(args.key, args.planner, args.module, delegates or {}))
    elif args.key:
        parser.error("--key needs --planner MODULE:CLASS or --module MODULE")
    for item in args.serve:
        key, sep, planner = item.partition("=")
        if not sep:
            parser.error(f"--serve {item!r} is not PREFIX=MODULE:CLASS")
        specs.append(PlannerSpec(key, planner))
    if args.config:
        specs += specs_from_yaml(args.config)
    if not specs:
        parser.error("nothing to serve: give --key with --planner/--module, --serve or --config")
    for spec in specs:
        try:
            validate_prefix(spec.key)
        except ValueError as exc:
            parser.error(str(exc))
    return specs


def specs_from_yaml(path: Path) -> list[PlannerSpec]:
    try:
        data: Any = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise PlannerLoadError(f"cannot read {path}: {exc}") from exc
    entries = data.get("planners") if isinstance(data, dict) else None
    if not isinstance(entries, list):
        raise PlannerLoadError(f"{path}: expected a top-level 'planners:' list")
    specs = []
    for i, entry in enumerate(entries):
        if not isinstance(entry, dict) or "key" not in entry:
            raise PlannerLoadError(f"{path}: planners[{i}] needs a 'key'")
        if ("planner" in entry) == ("module" in entry):
            raise PlannerLoadError(f"{path}: planners[{i}] needs exactly one of planner / module")
        delegates = entry.get("delegates") or {}
        if not isinstance(delegates, dict):
            raise PlannerLoadError(
                f"{path}: planners[{i}].delegates must map roles to functions, e.g. "
                "{compute_velocity_commands: compute}"
            )
        kind = entry.get("kind")
        try:
            check_roles(delegates)
            if kind is not None and kind not in KIND_ROLES:
                raise PlannerLoadError(
                    f"kind {kind!r} is not a main role; main roles: {', '.join(KIND_ROLES)}"
                )
        except PlannerLoadError as exc:
            raise PlannerLoadError(f"{path}: planners[{i}]: {exc}") from None
        specs.append(
            PlannerSpec(
                str(entry["key"]),
                entry.get("planner"),
                entry.get("module"),
                {str(k): str(v) for k, v in delegates.items()},
                kind,
                batch=entry.get("batch") is True,
            )
        )
    return specs


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    given = sys.argv[1:] if argv is None else argv
    # --help must work whatever the environment holds; otherwise variables fill the options.
    from_environment = {} if {"-h", "--help"} & set(given) else apply_environment(parser)
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=args.log_level, format="[%(asctime)s] [%(levelname)s] [%(name)s] %(message)s"
    )
    if args.parent_tmpdir is not None and args.parent_pid is None:
        parser.error("--parent-tmpdir needs --parent-pid")
    if args.respawn:
        os.environ.pop("NAV2_PYIF_RESPAWN", None)  # the child serves, it keeps nothing
        os.environ.pop("NAV2_PYIF_PARENT_PID", None)  # the child's parent is this keeper
        child = [sys.executable, "-m", "nav2_pyif.server.cli", *without_respawn(given)]
        return keep([*child, "--parent-pid", str(os.getpid())], parent=args.parent_pid)
    if args.parent_pid is not None:
        if args.parent_tmpdir is not None:
            remove_when_orphaned(args.parent_pid, args.parent_tmpdir)
        if not bind_to_parent(args.parent_pid):
            print(f"planner-host: parent {args.parent_pid} is gone; not starting", file=sys.stderr)
            return 1
    # A planner served in this process (--isolation none) that segfaults leaves its stack.
    faulthandler.enable()
    log = logging.getLogger("nav2_pyif.server.host")
    for name, value in sorted(from_environment.items()):
        log.info("from the environment: %s=%s", name, value)
    check_serialization_rmw()  # before any worker starts: they inherit the environment
    apply_xla_threads(args.xla_threads, log)  # the same, and before any planner starts JAX
    for directory in [os.getcwd(), *args.path][::-1]:
        if directory not in sys.path:
            sys.path.insert(0, directory)
    host_id = new_host_id()
    # Signals from the start: a SIGTERM while the workers load still stops them. SIGHUP
    # reloads every planner once serving; before that it stops the host like the others.
    stop, serving, reload_requested = threading.Event(), threading.Event(), threading.Event()
    stopped_by: list[int] = []
    edited: set[str] = set()  # --watch: the keys whose sources changed, reloaded in the loop
    edited_lock = threading.Lock()

    def on_edit(keys: set[str], files: list[Path]) -> None:
        log.info("--watch: %s changed: reloading %s", ", ".join(map(str, files)), ", ".join(keys))
        with edited_lock:
            edited.update(keys)
        stop.set()

    def on_signal(signum: int, _frame: FrameType | None) -> None:
        if signum == signal.SIGHUP and serving.is_set():
            reload_requested.set()
        elif not stopped_by:
            log.info("received %s, shutting down", signal.Signals(signum).name)
            stopped_by.append(signum)
        stop.set()

    for signum in TERMINATING:
        signal.signal(signum, on_signal)
    if args.reload_allow and not args.allow_remote_reload:
        parser.error("--reload-allow needs --allow-remote-reload")
    check_batch_arguments(args, parser)
    if args.watch and watchfiles_missing():
        parser.error(str(watchfiles_missing()))
    if args.pid_file and not os.access(args.pid_file.parent, os.W_OK):
        parser.error(f"--pid-file {args.pid_file}: its directory is missing or not writable")
    try:
        specs = collect_specs(args, parser)
        check_record_arguments(args, parser, [spec.key for spec in specs])
        services = start_services(specs, host_id, args)
    except PlannerLoadError as exc:
        print(f"planner-host: error: {exc}", file=sys.stderr)
        return exit_code(stopped_by[0]) if stopped_by else 2
    options = options_from_args(args)
    zenoh.try_init_log_from_env()  # Zenoh's own log (e.g. why a TLS link failed) on $RUST_LOG
    try:
        session = open_session(options)
    except (ConnectionError, FileNotFoundError) as exc:
        for service in services:
            service.close()
        print(f"planner-host: error: {exc}", file=sys.stderr)
        return 3
    served, recorder = start_recording(args, specs, services)
    served, live = start_live_tap(args, session, specs, served)
    cleanup_watch: list[Callable[[], None]] = []
    host = PlannerHost(
        session,
        host_id,
        ReloadPolicy(args.allow_remote_reload, tuple(args.reload_allow)),
        live=live,
    )
    try:
        if not stopped_by:
            for spec, service in zip(specs, served, strict=True):
                host.serve(spec.key, service)
            serving.set()
            settle_heap()  # what start-up built serves as long as the host
            log.info(
                "host %s ready (%d planner%s, isolation: %s)",
                host_id,
                len(services),
                "s"[: len(services) > 1],
                args.isolation,
            )
            if args.pid_file:
                write_pid_file(args.pid_file)
        reach = ReachWatch(session, *configured_endpoints(options))
        if args.watch and not stopped_by:
            watcher = SourceWatcher({s.key: source_roots(s) for s in specs}, on_edit).start()
            cleanup_watch.append(watcher.stop)
        while not stopped_by:
            if not stop.wait(1.0):
                reach.check()
                continue
            stop.clear()
            with edited_lock:
                keys, edited_now = set(edited), bool(edited)
                edited.clear()
            if edited_now and not stopped_by:
                host.reload_all(keys)
            if reload_requested.is_set() and not stopped_by:
                reload_requested.clear()
                log.info("SIGHUP: reloading every planner")
                host.reload_all()
    finally:
        # Close explicitly on every path: an open session keeps the process alive. Services
        # not yet served (a signal during start-up) are closed too: no worker outlives us.
        for stop_watching in cleanup_watch:
            stop_watching()
        if args.pid_file:
            remove_pid_file(args.pid_file)
        host.close()
        if live is not None:
            live.close()  # its streams' publishers, before the session goes
        if recorder is not None:
            recorder.close()  # after the host: every call answered is in the files
        for service in services:
            service.close()
        session.close()
    return exit_code(stopped_by[0]) if stopped_by else 0


def start_services(
    specs: list[PlannerSpec], host_id: str, args: argparse.Namespace
) -> list[PlannerService]:
    """Start every planner, one per key or one per batch group (batch_groups); workers load
    in parallel (a fleet host may serve dozens). If one cannot load, the others are stopped
    and its PlannerLoadError is raised."""
    return start_all(specs, host_id, args, lambda spec: start_service(spec, host_id, args))


def start_service(spec: PlannerSpec, host_id: str, args: argparse.Namespace) -> PlannerService:
    if args.isolation == "none":
        return InProcessPlanner(spec, host_id)
    deadlines = Deadlines(call=args.deadline, plan=args.plan_deadline, hang_grace=args.hang_grace)
    return SupervisedPlanner(
        spec,
        host_id,
        deadlines=deadlines,
        memory_limit=args.memory_limit * 2**20 or None,
        log_level=args.log_level,
    ).start()


if __name__ == "__main__":
    sys.exit(main())
