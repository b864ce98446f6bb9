"""The user's Nav2 params file, read as Nav2 reads it, so that the runner judges a planner as
Nav2 will with that same file: controller_server's ``controller_frequency`` and
``failure_tolerance``, its first goal checker's tolerances, and the nav2_pyif plugins of
controller_server and planner_server (the planner they name, their parameters, their
timeouts). What the caller gives explicitly wins over the file, the file over the runner's
defaults."""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from nav2_pyif_protocol.bridge_params import BY_NAME

from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.params import ParamValue
from nav2_pyif.roles import parse_delegates
from nav2_pyif.runner.run import SimConfig, SimError

log = logging.getLogger("nav2_pyif.runner")

#: Read from the current directory when present and no other file is named.
DEFAULT_FILE = Path("nav2_params.yaml")
BRIDGE_PREFIX = "nav2_pyif_bridge::"
#: Nav2's goal checkers whose tolerances the runner's own check applies.
GOAL_CHECKERS = ("nav2_controller::SimpleGoalChecker", "nav2_controller::StoppedGoalChecker")


class Nav2ParamsError(ValueError):
    """The params file cannot be read, or a value in it is not what Nav2 would accept."""


@dataclass
class PluginSection:
    """One nav2_pyif plugin of the file (``FollowPath``, ``GridBased``)."""

    name: str
    spec: str | None  # python_planner, else python_module; None: a host serves its key
    delegates: dict[str, str]  # python_delegates
    path: list[str]  # python_path
    timeout: float | None  # the bridge's timeout for the run's calls of this plugin
    params: dict[str, ParamValue]  # every other parameter: the planner's own


@dataclass
class Nav2Params:
    path: Path
    options: dict[str, Any] = field(default_factory=dict)  # SimConfig fields the file sets
    read: list[str] = field(default_factory=list)  # what was read, for the log and report

    def describe(self) -> str:
        return f"{self.path}: " + ("; ".join(self.read) or "nothing the runner uses")


def _ros_parameters(data: Mapping[str, Any], node: str) -> dict[str, Any]:
    """``node``'s ros__parameters (a namespaced node name, /robot1/controller_server, too)."""
    for name, section in data.items():
        if str(name).rsplit("/", 1)[-1] == node and isinstance(section, dict):
            params = section.get("ros__parameters")
            return params if isinstance(params, dict) else {}
    return {}


def _seconds(where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise Nav2ParamsError(f"{where}: {value!r} is not a number")
    if value <= 0:
        raise Nav2ParamsError(f"{where}: {value!r} must be > 0")
    return float(value)


def _flattened(section: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """Nested parameters as ROS names them: ``{"scan": {"topic": "/scan"}}`` -> scan.topic."""
    out: dict[str, Any] = {}
    for name, value in section.items():
        if isinstance(value, dict):
            out.update(_flattened(value, f"{prefix}{name}."))
        else:
            out[f"{prefix}{name}"] = value
    return out


def _names(value: Any) -> list[str]:
    """A string-or-list-of-strings parameter (Kind.STRINGS)."""
    if value in (None, "", []):
        return []
    return [str(v) for v in value] if isinstance(value, list) else [str(value)]


def _plugin(where: str, name: str, section: Mapping[str, Any], timeout: str) -> PluginSection:
    """A nav2_pyif plugin's section: the bridge's own parameters apart from the planner's."""
    flat = _flattened(section)
    inputs = _names(flat.get("inputs"))
    delegates = section.get("python_delegates")
    if isinstance(delegates, dict):  # nested python_delegates.<role>: function
        delegates = [f"{role}={function}" for role, function in delegates.items()]
    try:
        delegate_map = parse_delegates(_names(delegates))
    except PlannerLoadError as exc:
        raise Nav2ParamsError(f"{where}.python_delegates: {exc}") from None
    bridge = {
        n
        for n in flat
        if n == "plugin"
        or n in BY_NAME
        or any(n.startswith(f"{b}.") for b in ("python_delegates", *inputs))
    }
    return PluginSection(
        name=name,
        spec=section.get("python_planner") or section.get("python_module"),
        delegates=delegate_map,
        path=_names(section.get("python_path")),
        timeout=_seconds(f"{where}.{timeout}", flat[timeout]) if timeout in flat else None,
        params={n: v for n, v in flat.items() if n not in bridge},
    )


def _first_plugin(
    params: Mapping[str, Any], node: str, list_name: str, default: str
) -> tuple[str, str, dict[str, Any]]:
    """(name, where, section) of the first plugin ``list_name`` names (Nav2's default)."""
    names = _names(params.get(list_name)) or [default]
    section = params.get(names[0])
    return names[0], f"{node}.{names[0]}", section if isinstance(section, dict) else {}


def _controller_server(params: Mapping[str, Any], found: Nav2Params) -> None:
    opts, node = found.options, "controller_server"
    if "controller_frequency" in params:
        opts["rate"] = _seconds(f"{node}.controller_frequency", params["controller_frequency"])
        found.read.append(f"controller_frequency {opts['rate']:g} Hz")
    if "failure_tolerance" in params:
        value = params["failure_tolerance"]
        if value != -1.0:  # -1: Nav2 never aborts; the run's timeout ends it instead
            where = f"{node}.failure_tolerance"
            opts["failure_tolerance"] = 0.0 if value == 0 else _seconds(where, value)
    name, where, section = _first_plugin(params, node, "goal_checker_plugins", "goal_checker")
    if section.get("plugin") in GOAL_CHECKERS:
        checker = {k: v for k, v in section.items() if k != "plugin"}
        opts["goal_checker"] = GoalTolerances(
            _seconds(f"{where}.xy_goal_tolerance", checker.get("xy_goal_tolerance", 0.25)),
            _seconds(f"{where}.yaw_goal_tolerance", checker.get("yaw_goal_tolerance", 0.25)),
            float(checker.get("trans_stopped_velocity", 0.25)),
            float(checker.get("rot_stopped_velocity", 0.25)),
        )
        opts["stateful_goal_check"] = bool(checker.get("stateful", True))
        t = opts["goal_checker"]
        found.read.append(
            f"goal checker {name} (xy {t.xy_goal_tolerance:g} m, yaw {t.yaw_goal_tolerance:g} rad)"
        )
    name, where, section = _first_plugin(params, node, "controller_plugins", "FollowPath")
    if str(section.get("plugin", "")).startswith(BRIDGE_PREFIX):
        plugin = _plugin(where, name, section, "timeout")
        _take(plugin, "controller", found)
        if plugin.timeout is not None:
            opts["call_timeout"] = plugin.timeout


def _planner_server(params: Mapping[str, Any], found: Nav2Params) -> None:
    name, where, section = _first_plugin(params, "planner_server", "planner_plugins", "GridBased")
    if str(section.get("plugin", "")).startswith(BRIDGE_PREFIX):
        plugin = _plugin(where, name, section, "plan_timeout")
        _take(plugin, "planner", found)
        if plugin.timeout is not None:
            found.options["plan_wait"] = plugin.timeout


def _take(plugin: PluginSection, role: str, found: Nav2Params) -> None:
    """A nav2_pyif plugin's planner, parameters, delegates and import path as the run's."""
    opts = found.options
    if plugin.spec:
        opts[role] = plugin.spec
    opts[f"{role}_params"] = plugin.params
    if plugin.delegates:
        opts.setdefault("delegates", {})[role] = plugin.delegates
    if plugin.path:
        opts.setdefault("path", []).extend(plugin.path)
    served = plugin.spec or "served by a host of its own (its key)"
    found.read.append(f"{role} {plugin.name} ({served}, {len(plugin.params)} parameters)")


def read_nav2_params(path: Path) -> Nav2Params:
    """The SimConfig fields ``path`` sets; Nav2ParamsError names what is wrong in it."""
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise Nav2ParamsError(f"cannot read Nav2 params file {path}: {exc}") from None
    if not isinstance(data, dict):
        raise Nav2ParamsError(f"{path}: not a Nav2 params file (no node sections)")
    found = Nav2Params(path)
    try:
        _controller_server(_ros_parameters(data, "controller_server"), found)
        _planner_server(_ros_parameters(data, "planner_server"), found)
    except Nav2ParamsError as exc:
        raise Nav2ParamsError(f"{path}: {exc}") from None
    return found


#: SimConfig fields whose values merge (the file's, then the caller's on top).
MERGED = ("controller_params", "planner_params", "delegates")


def merged(from_file: Mapping[str, Any], given: Mapping[str, Any]) -> dict[str, Any]:
    """SimConfig fields: the caller's over the file's; parameters and delegates merge name by
    name, import paths add up."""
    out = {**from_file, **given}
    for name in MERGED:
        if name in from_file and name in given:
            out[name] = {**from_file[name], **given[name]}
    if "path" in from_file and "path" in given:
        out["path"] = [*given["path"], *from_file["path"]]
    return out


#: ``params_file`` default: ./nav2_params.yaml when there is one.
AUTO = "auto"


def params_file_to_read(params_file: str | Path | None) -> Path | None:
    """AUTO: DEFAULT_FILE when present; None: none; else that file."""
    if params_file is None:
        return None
    if str(params_file) == AUTO:
        return DEFAULT_FILE if DEFAULT_FILE.is_file() else None
    return Path(params_file)


def sim_config(map: Path, params_file: str | Path | None = AUTO, **given: Any) -> SimConfig:
    """A run's SimConfig: ``given`` (SimConfig's fields; None counts as not given) over the
    Nav2 params file's, over the runner's defaults. SimError names what is wrong in the
    file."""
    given = {name: value for name, value in given.items() if value is not None}
    path = params_file_to_read(params_file)
    if path is None:
        return SimConfig(map=map, **given)
    try:
        found = read_nav2_params(path)
    except Nav2ParamsError as exc:
        raise SimError(str(exc)) from None
    log.info("Nav2 params from %s", found.describe())
    return SimConfig(map=map, params_file=path, **merged(found.options, given))
