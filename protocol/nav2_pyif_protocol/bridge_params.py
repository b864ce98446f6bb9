"""The Nav2 plugin's own parameters: the one table of them.

Every other parameter under a plugin's namespace (``FollowPath.max_vel_x``) goes to the
planner in configure; these are the bridge's. From this table ``generate`` writes the C++
settings (``bridge_plugin/include/nav2_pyif_bridge/client/bridge_parameters.hpp``: the
members, their defaults, which ``ros2 param set`` may change on a running plugin, the parsing
of each) and the parameter table of ``bridge_plugin/README.md``; the reference client's
``Timeouts`` take their defaults from it.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from nav2_pyif_protocol.schema import Timeout


class Kind(str, Enum):
    """How a parameter's value is read (the C++ reader of each: settings.cpp)."""

    STRING = "string"
    STRINGS = "strings"  # a string or a list of strings ("" and [] are none)
    SECONDS = "seconds"  # a number > 0


@dataclass(frozen=True)
class BridgeParam:
    name: str
    kind: Kind
    default: str | float | None  # None: empty (a string, a list) or unset
    live: bool  # ros2 param set takes it on a running plugin; else read at configure
    doc: str
    shown_default: str | None = None  # README's default column, when not the value itself
    timeout: Timeout | None = None  # the timeout class it sets (Timeouts' member)
    aliases: tuple[str, ...] = ()  # older names read as this one


#: A local host imports, JIT-compiles and starts a worker before it answers: configure waits
#: this long for it unless ``wait_for_host`` says otherwise.
LOCAL_HOST_WAIT_FOR_HOST = 60.0

BRIDGE_PARAMS: tuple[BridgeParam, ...] = (
    BridgeParam(
        "key",
        Kind.STRING,
        None,
        False,
        "Zenoh key prefix the planner host serves (e.g. `nav2_pyif/robot1/FollowPath`); with a "
        "local host, optional",
    ),
    BridgeParam(
        "zenoh_config",
        Kind.STRING,
        None,
        False,
        "Zenoh JSON5 config file (zenoh-c backend only); unset: `$NAV2_PYIF_ZENOH_CONFIG`, else "
        "the package's shipped `config/default_session.json5`",
        shown_default="`$NAV2_PYIF_ZENOH_CONFIG`",
    ),
    BridgeParam(
        "zenoh_connect",
        Kind.STRINGS,
        None,
        False,
        "endpoints to connect to (a router, or a host started with `--listen`), replacing the "
        "config file's",
        shown_default="`tcp/localhost:7447`",
    ),
    BridgeParam(
        "timeout",
        Kind.SECONDS,
        0.04,
        True,
        "compute_velocity_commands, set_plan, set_speed_limit, cancel, reset, the checkers' and "
        "the layer's calls: keep it below the control period",
        timeout=Timeout.CALL,
    ),
    BridgeParam(
        "configure_timeout",
        Kind.SECONDS,
        10.0,
        True,
        "configure (imports, JIT compilation)",
        timeout=Timeout.CONFIGURE,
    ),
    BridgeParam(
        "plan_timeout",
        Kind.SECONDS,
        5.0,
        True,
        "create_plan; smooth (at least SmoothPath's `max_smoothing_duration` + 1 s)",
        timeout=Timeout.PLAN,
    ),
    BridgeParam(
        "lifecycle_timeout",
        Kind.SECONDS,
        5.0,
        True,
        "activate, deactivate, cleanup, set_parameters",
        timeout=Timeout.LIFECYCLE,
    ),
    BridgeParam(
        "wait_for_host",
        Kind.SECONDS,
        5.0,
        True,
        "how long configure waits for a host; without one, Nav2 comes up anyway and the first "
        "call configures the planner",
        shown_default=f"5 s ({LOCAL_HOST_WAIT_FOR_HOST:g} s with a local host)",
    ),
    BridgeParam(
        "python_module",
        Kind.STRING,
        None,
        False,
        "the function-delegate style: the plugin starts and supervises its own `planner-host` "
        "for this module of functions (`--module`)",
    ),
    BridgeParam(
        "python_delegates",
        Kind.STRINGS,
        None,
        False,
        'its role -> function map, given to the host as `--delegate` items (`["role=function", '
        '...]`, one `"r=f,r2=f2"` string, or nested `python_delegates.<role>: function`); '
        "without it, the module's functions named after the roles",
    ),
    BridgeParam(
        "python_planner",
        Kind.STRING,
        None,
        False,
        "or a planner class, `module:Class`, for the local host (`--planner`)",
    ),
    BridgeParam(
        "python_path",
        Kind.STRINGS,
        None,
        False,
        "where the local host imports planners from (`--path`)",
    ),
    BridgeParam(
        "planner_host_command",
        Kind.STRING,
        "planner-host",
        False,
        "the executable that runs the local host",
        aliases=("planner_host_executable",),
    ),
    BridgeParam(
        "planner_host_args",
        Kind.STRINGS,
        None,
        False,
        'more arguments for the local host (e.g. `["--isolation", "none"]`)',
    ),
    BridgeParam(
        "inputs",
        Kind.STRINGS,
        None,
        False,
        'controllers: extra topics (e.g. `["scan"]` with `scan.topic: /scan`, `scan.type: '
        "sensor_msgs/msg/LaserScan`), subscribed on controller_server's node; the latest message "
        "of each goes with the next call, serialized, only when new; the planner reads "
        '`self.inputs["scan"]`',
    ),
)

BY_NAME: dict[str, BridgeParam] = {p.name: p for p in BRIDGE_PARAMS}


def default_seconds(name: str) -> float:
    """The default of a parameter in seconds (``wait_for_host``, ``timeout``, ...)."""
    default = BY_NAME[name].default
    assert isinstance(default, float), name
    return default


def timeout_default(timeout: Timeout) -> float:
    """The default seconds of a timeout class (the parameter that sets it)."""
    (name,) = (p.name for p in BRIDGE_PARAMS if p.timeout is timeout)
    return default_seconds(name)
