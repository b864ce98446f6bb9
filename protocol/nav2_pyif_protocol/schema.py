"""The one description of the protocol: every field of every message, in wire order.

Encoders write map keys in exactly this order (so both codecs produce identical bytes);
decoders check types and required fields and ignore keys they do not know. The Python codec
compiles its validators from these tables when it is imported; ``generate`` renders them as
the C++ message structs and their codec (bridge_plugin/) and as PROTOCOL.md's field tables:

    python -m nav2_pyif_codegen.generate    # after any edit here
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Final

from nav2_pyif_protocol.constants import BehaviorFailure, BehaviorStatus, Op, PluginType

# Field kinds. A struct kind is the name of an entry of STRUCTS.
INT: Final = "int"  # msgpack int, fits int64
UINT: Final = "uint"  # msgpack int >= 0, fits uint64
UINT32: Final = "uint32"  # msgpack int >= 0, fits uint32
FLOAT: Final = "float"  # msgpack float64, always (even for whole numbers)
BOOL: Final = "bool"
STR: Final = "str"  # UTF-8 msgpack str
BIN: Final = "bin"  # msgpack bin
FLOAT6: Final = "float[6]"  # msgpack array of 6 float64
FLOAT7: Final = "float[7]"  # msgpack array of 7 float64
PARAMS: Final = "params"  # map str -> bool | int | float | str | array of one of those
STR_MAP: Final = "map<str,str>"
BODY: Final = "body"  # envelopes only: the op's body, a map of the fields BODIES gives it


class Role(str, Enum):
    """What an envelope field is beside its kind: a rule of its own in both codecs."""

    #: Read before any other field (a message of another version may differ in anything
    #: else); a value other than PROTOCOL_VERSION is VersionMismatch.
    VERSION = "version"
    #: The name of the op whose body the envelope's BODY field is: an Op's value, or
    #: BadRequest. The C++ Request derives it from its body's type, so the two always agree.
    OP = "op"


#: Packed float64 arrays (``bin``): row name -> (values per row, what a row holds).
ROWS: dict[str, tuple[int, str]] = {
    "Pose": (7, "x, y, z, qx, qy, qz, qw"),
    "Footprint": (2, "x, y"),
}


@dataclass(frozen=True)
class Field:
    name: str
    kind: str
    required: bool = True
    doc: str = ""
    #: BIN only: packed little-endian float64 rows of this ROWS entry (a whole number of them).
    rows: str = ""
    #: BIN only: its byte count is the product of these int fields of the same map.
    cells: tuple[str, ...] = ()
    #: FLOAT6 / FLOAT7 only: the value a new C++ struct starts with (all zeros when empty).
    default: tuple[float, ...] = ()
    #: A msgpack array of values of ``kind`` (a structure or STR), possibly empty.
    many: bool = False
    #: INT / UINT only: the smallest value decoders accept (also a new C++ struct's value).
    minimum: int | None = None
    #: Envelopes only: the field's rule beyond its kind (see Role).
    role: Role | None = None
    #: BOOL, envelopes only: the two optional fields it chooses between, exactly one of them
    #: sent: the first when it is true, the second when false (a reply's body or error). The
    #: chosen one must be there, but for a BODY field, which reads as {} when left out. The
    #: C++ holds the two as one std::variant; the flag is which alternative it holds.
    selects: tuple[str, str] | None = None


def _f(
    name: str,
    kind: str,
    doc: str = "",
    required: bool = True,
    *,
    rows: str = "",
    cells: tuple[str, ...] = (),
    default: tuple[float, ...] = (),
    many: bool = False,
    minimum: int | None = None,
    role: Role | None = None,
    selects: tuple[str, str] | None = None,
) -> Field:
    return Field(name, kind, required, doc, rows, cells, default, many, minimum, role, selects)


#: What each structure is, for the generated C++ and PROTOCOL.md.
STRUCT_DOCS: dict[str, str] = {
    "PoseStamped": "A stamped pose, in the costmap's global frame.",
    "TwistStamped": "A stamped velocity, in the robot base frame.",
    "Path": "A plan: poses packed as float64 rows (one 56-byte row per pose, not 7 floats).",
    "Costmap": "Nav2's Costmap2D: metadata, the raw cost bytes and the footprint.",
    "GoalChecker": "The goal checker's tolerances.",
    "Error": "The error of a failed reply (PROTOCOL.md section 7).",
    "Input": "The latest message of one of the plugin's input topics, ROS-serialized (CDR).",
    "DebugOutput": "A message the planner publishes for debugging, ROS-serialized (CDR).",
    "CarriedCall": "One call carried in another plugin's query (PROTOCOL.md section 15).",
}


STRUCTS: dict[str, tuple[Field, ...]] = {
    "PoseStamped": (
        _f("frame_id", STR, "frame of the pose"),
        _f("stamp_ns", INT, "header stamp, ns since the epoch of the ROS clock"),
        _f(
            "pose",
            FLOAT7,
            "x, y, z [m], qx, qy, qz, qw",
            default=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0),  # the identity, not all-zero
        ),
    ),
    "TwistStamped": (
        _f("frame_id", STR, "frame of the twist (the robot base frame)"),
        _f("stamp_ns", INT, "header stamp [ns]"),
        _f("twist", FLOAT6, "vx, vy, vz [m/s], wx, wy, wz [rad/s]"),
    ),
    "Path": (
        _f("frame_id", STR, "frame of every pose"),
        _f("stamp_ns", INT, "header stamp [ns]"),
        _f(
            "poses",
            BIN,
            "N x 7 float64 little-endian, row-major: x, y, z, qx, qy, qz, qw",
            rows="Pose",
        ),
    ),
    "Costmap": (
        _f("version", UINT, "client's counter; changes whenever data or metadata change"),
        _f("frame_id", STR, "the costmap's global frame"),
        _f("size_x", UINT32, "cells along x (width)"),
        _f("size_y", UINT32, "cells along y (height)"),
        _f("resolution", FLOAT, "m per cell"),
        _f("origin_x", FLOAT, "world x of cell (0, 0)'s outer corner [m]"),
        _f("origin_y", FLOAT, "world y of cell (0, 0)'s outer corner [m]"),
        _f(
            "data",
            BIN,
            "size_x * size_y uint8 costs, index = my * size_x + mx",
            cells=("size_x", "size_y"),
        ),
        _f(
            "footprint",
            BIN,
            "K x 2 float64 little-endian x, y [m] in the robot frame; K may be 0",
            rows="Footprint",
        ),
        _f("robot_radius", FLOAT, "[m]; used when the footprint is empty"),
    ),
    "GoalChecker": (
        _f("xy_goal_tolerance", FLOAT, "[m]"),
        _f("yaw_goal_tolerance", FLOAT, "[rad]"),
        _f("trans_stopped_velocity", FLOAT, "[m/s]"),
        _f("rot_stopped_velocity", FLOAT, "[rad/s]"),
        _f(
            "path_length_tolerance",
            FLOAT,
            "[m] the remaining plan length within which the goal may count as reached "
            "(Lyrical's getTolerances); absent when the checker has none, or before Lyrical",
            False,
        ),
    ),
    "Error": (
        _f("type", STR, "nav2_core exception name or protocol error name"),
        _f("message", STR, "human-readable, names the cause"),
        _f("traceback", STR, "Python traceback, empty when none"),
        _f("python_type", STR, "qualified name of the Python exception, empty when none"),
    ),
    "Input": (
        _f("name", STR, "the input's name in the plugin's `inputs` parameter (e.g. scan)"),
        _f("type", STR, "ROS message type, e.g. sensor_msgs/msg/LaserScan"),
        _f("stamp_ns", INT, "when the plugin received it, ns on the server's clock"),
        _f("cdr", BIN, "the message as ROS serializes it (CDR with its 4-byte header)"),
    ),
    "DebugOutput": (
        _f("name", STR, "the output's name: published on <plugin name>/<name>"),
        _f("type", STR, "ROS message type, one the configure reply listed for this name"),
        _f("cdr", BIN, "the message as ROS serializes it (CDR with its 4-byte header)"),
    ),
    "CarriedCall": (
        _f("key", STR, "key prefix of the plugin it is for"),
        _f("payload", BIN, "its encoded request (in a request) or reply (in a reply)"),
    ),
}

REQUEST_ENVELOPE: tuple[Field, ...] = (
    _f("v", INT, "protocol version", role=Role.VERSION),
    _f("op", STR, "operation (also the last key chunk)", role=Role.OP),
    _f("sid", STR, "session id chosen by the client at configure"),
    _f(
        "epoch",
        UINT,
        "session epoch: 1 at the first configure, +1 at each re-establishment",
        minimum=1,
    ),
    _f("seq", UINT, "per-plugin sequence number, strictly increasing across epochs"),
    _f("body", BODY, "operation-specific map"),
)

REPLY_ENVELOPE: tuple[Field, ...] = (
    _f("v", INT, "protocol version", role=Role.VERSION),
    _f("seq", UINT, "the request's seq"),
    _f("ok", BOOL, "true: body follows; false: error follows", selects=("body", "error")),
    _f("body", BODY, "operation-specific map (ok replies)", required=False),
    _f("error", "Error", "failure (error replies)", required=False),
    _f("host", STR, "id of the host that answered"),
    _f("compute_ns", INT, "time spent in the planner's method [ns]; 0 when not called"),
)

_CONFIGURE_REQUEST = (
    _f(
        "plugin_type",
        STR,
        "'controller', 'global_planner', 'smoother', 'goal_checker', 'progress_checker', "
        "'costmap_layer', 'behavior' or 'path_handler'",
    ),
    _f("name", STR, "plugin name in Nav2 (e.g. FollowPath)"),
    _f("node", STR, "name of the Nav2 server node"),
    _f("params", PARAMS, "every parameter under the plugin's namespace, prefix stripped"),
    _f(
        "global_frame",
        STR,
        "the costmap's global frame (a behaviour's: behavior_server's local_frame)",
    ),
    _f("robot_base_frame", STR, "the robot base frame"),
    _f(
        "costmap",
        "Costmap",
        "the costmap at configure time (0 x 0 when the plugin has none: a progress checker, "
        "a smoother before its costmap subscription delivered one)",
    ),
    _f(
        "nav2_params",
        PARAMS,
        "Nav2's parameters outside the plugin's namespace that a planner may need, by their "
        "Nav2 names: controller_frequency [Hz] (controller_server's), inflation_radius [m] and "
        "cost_scaling_factor [1/m] (the costmap's inflation layer); absent when none is known",
        required=False,
    ),
)

#: op -> (request body fields, reply body fields)
# The rest of the control cycle, carried in one of its calls' query (PROTOCOL.md section 15):
# which ops may carry which is CARRIES below.
_CARRY = _f(
    "carry",
    "CarriedCall",
    "calls to run after this one, in order, as far as Nav2 would go; absent when none",
    False,
    many=True,
)
_CARRIED = _f(
    "carried",
    "CarriedCall",
    "the replies of the carried calls that ran, in order; absent when none ran",
    False,
    many=True,
)

# A behaviour's step (PROTOCOL.md section 17): TimedBehavior's ResultStatus, by name.
_BEHAVIOR_STATUS = (
    _f(
        "status",
        STR,
        ", ".join(repr(s.value) for s in BehaviorStatus).replace(", 'running'", " or 'running'")
        + " (on_run: not 'running')",
    ),
    _f(
        "failure",
        STR,
        "why it failed, mapped to the action's error code: "
        + ", ".join(f"{f.value!r}" + (" (none)" if not f.value else "") for f in BehaviorFailure),
    ),
)

BODIES: dict[Op, tuple[tuple[Field, ...], tuple[Field, ...]]] = {
    Op.CONFIGURE: (
        _CONFIGURE_REQUEST,
        (
            _f("declared", PARAMS, "parameters the planner declared, with current values"),
            _f(
                "planner",
                STR,
                "what the host serves on this key, e.g. pkg.module:Class (for logs and "
                "reports; older hosts leave it out)",
                False,
            ),
            _f(
                "undeclared",
                STR_MAP,
                "given parameters the planner does not declare (ignored), name -> reason; "
                "absent when none",
                required=False,
            ),
            _f(
                "debug_outputs",
                STR_MAP,
                "debug outputs the planner may return, name -> ROS message type; absent when none",
                required=False,
            ),
        ),
    ),
    Op.ACTIVATE: ((), ()),
    Op.DEACTIVATE: ((), ()),
    Op.CLEANUP: ((), ()),
    Op.SET_PARAMETERS: (
        (_f("params", PARAMS, "changed parameters"),),
        (_f("rejected", STR_MAP, "name -> reason, for each change not applied"),),
    ),
    Op.SET_PLAN: (
        (
            _f(
                "path",
                "Path",
                "the plan to follow, in the costmap's global frame (section 14); a path "
                "handler's, to cut segments from, in its own frame (section 19)",
            ),
            _f(
                "goal",
                "PoseStamped",
                "the global goal, same frame: Nav2's (Lyrical); absent: the plan's last pose",
                False,
            ),
        ),
        (),
    ),
    Op.COMPUTE_VELOCITY_COMMANDS: (
        (
            _f("pose", "PoseStamped", "robot pose, in the costmap's global frame"),
            _f("velocity", FLOAT6, "current velocity in the robot base frame"),
            _f("goal_checker", "GoalChecker", "tolerances, when Nav2 gave a goal checker", False),
            _f("costmap", "Costmap", "present only when changed since last sent", False),
            _f(
                "plan",
                "Path",
                "the plan Nav2 transformed for this cycle, costmap's global frame (Lyrical); "
                "present only when it changed since the host last got it",
                False,
            ),
            _f(
                "goal",
                "PoseStamped",
                "the global goal, same frame (Lyrical); present only when it changed since "
                "the host last got it",
                False,
            ),
            _f(
                "inputs",
                "Input",
                "input messages received since the last call (the latest of each); absent "
                "when none",
                False,
                many=True,
            ),
            _f(
                "debug_wanted",
                STR,
                "names of the debug outputs someone subscribes to; absent when none",
                False,
                many=True,
            ),
            _CARRY,
        ),
        (
            _f("cmd_vel", "TwistStamped", "the command; every component finite"),
            _f(
                "debug",
                "DebugOutput",
                "debug outputs among debug_wanted the planner returned; absent when none",
                False,
                many=True,
            ),
            _CARRIED,
        ),
    ),
    Op.SET_SPEED_LIMIT: (
        (
            _f("speed_limit", FLOAT, "m/s, or percent of the maximum when percentage"),
            _f("percentage", BOOL, "speed_limit is a percentage"),
        ),
        (),
    ),
    Op.CANCEL: ((), (_f("cancelled", BOOL, "true when the controller finished cancelling"),)),
    Op.RESET: ((), ()),
    Op.CREATE_PLAN: (
        (
            _f("start", "PoseStamped", "start pose, in the costmap's global frame"),
            _f("goal", "PoseStamped", "goal pose, in the costmap's global frame"),
            _f("costmap", "Costmap", "present only when changed since last sent", False),
            _f(
                "viapoints",
                "Path",
                "poses to pass through, in order, same frame (Lyrical); absent when none",
                False,
            ),
        ),
        (_f("path", "Path", "the plan; every value finite"),),
    ),
    Op.CANCEL_PLAN: (
        (_f("target_seq", UINT, "seq of the create_plan call to cancel"),),
        (_f("accepted", BOOL, "true when that call was running and is now flagged"),),
    ),
    Op.SMOOTH: (
        (
            _f("path", "Path", "the path to smooth, in its own frame (Nav2 does not transform it)"),
            _f(
                "max_time",
                FLOAT,
                "time the smoother may take [s] (SmoothPath's max_smoothing_duration)",
            ),
            _f("costmap", "Costmap", "present only when changed since last sent", False),
        ),
        (
            _f("path", "Path", "the smoothed path, same frame; every value finite"),
            _f("was_completed", BOOL, "smooth()'s return: false when it stopped at max_time"),
        ),
    ),
    Op.IS_GOAL_REACHED: (
        (
            _f("pose", FLOAT7, "robot pose (x, y, z, qx, qy, qz, qw), the costmap's global frame"),
            _f("goal", FLOAT7, "goal pose, same frame"),
            _f("velocity", FLOAT6, "current velocity in the robot base frame"),
            _f(
                "xy_only",
                BOOL,
                "true: isGoalXYReached, the position only (Lyrical); absent: isGoalReached",
                False,
            ),
            _CARRY,
        ),
        (_f("reached", BOOL, "the goal is reached"), _CARRIED),
    ),
    Op.GET_TOLERANCES: (
        (),
        (
            _f("available", BOOL, "getTolerances' return: false when the checker has none"),
            _f(
                "pose_tolerance",
                FLOAT7,
                "x, y, z [m], qx, qy, qz, qw: the yaw tolerance as a quaternion",
                default=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0),
            ),
            _f("velocity_tolerance", FLOAT6, "vx, vy, vz [m/s], wx, wy, wz [rad/s]"),
            _f(
                "path_length_tolerance",
                FLOAT,
                "[m] (Lyrical's getTolerances); absent when the checker has none",
                False,
            ),
        ),
    ),
    Op.CHECK: (
        (
            _f("pose", "PoseStamped", "robot pose, in the costmap's global frame"),
            _CARRY,
        ),
        (
            _f("making_progress", BOOL, "check()'s return: false = failed to make progress"),
            _CARRIED,
        ),
    ),
    Op.UPDATE_BOUNDS: (
        (
            _f("robot_x", FLOAT, "robot x in the costmap's global frame [m]"),
            _f("robot_y", FLOAT, "robot y [m]"),
            _f("robot_yaw", FLOAT, "robot yaw [rad]"),
            _f("min_x", FLOAT, "the bounds so far (earlier layers'), world [m]"),
            _f("min_y", FLOAT, "[m]"),
            _f("max_x", FLOAT, "[m]"),
            _f("max_y", FLOAT, "[m]"),
        ),
        (
            _f("min_x", FLOAT, "the bounds grown to cover what this layer will change [m]"),
            _f("min_y", FLOAT, "[m]"),
            _f("max_x", FLOAT, "[m]"),
            _f("max_y", FLOAT, "[m]"),
        ),
    ),
    Op.UPDATE_COSTS: (
        (
            _f("min_i", INT, "the window to update: first cell column of the master grid"),
            _f("min_j", INT, "first cell row"),
            _f("max_i", INT, "one past the last column"),
            _f("max_j", INT, "one past the last row"),
            _f("origin_x", FLOAT, "the master grid's origin (cell (0, 0)'s corner) [m]"),
            _f("origin_y", FLOAT, "[m]"),
            _f("resolution", FLOAT, "m per cell"),
        ),
        (
            _f("width", UINT32, "max_i - min_i"),
            _f("height", UINT32, "max_j - min_j"),
            _f(
                "costs",
                BIN,
                "height * width uint8 costs of the window, row-major from (min_i, min_j)",
                cells=("width", "height"),
            ),
            _f(
                "combine",
                STR,
                "how they meet the master's: max, max_keep_unknown, overwrite, true_overwrite",
            ),
        ),
    ),
    Op.MATCH_SIZE: (
        (
            _f("size_x", UINT32, "the master grid's cells along x"),
            _f("size_y", UINT32, "cells along y"),
            _f("resolution", FLOAT, "m per cell"),
            _f("origin_x", FLOAT, "cell (0, 0)'s corner [m]"),
            _f("origin_y", FLOAT, "[m]"),
        ),
        (),
    ),
    Op.ON_RUN: (
        (
            _f("action", STR, "the action type, e.g. nav2_msgs/action/BackUp"),
            _f(
                "command",
                PARAMS,
                "the goal's fields as plain values (section 17), e.g. target_x [m], speed "
                "[m/s], time_allowance [s]",
            ),
            _f("pose", "PoseStamped", "robot pose, in behavior_server's local frame"),
            _f("costmap", "Costmap", "the local costmap, present only when changed", False),
        ),
        _BEHAVIOR_STATUS,
    ),
    Op.ON_CYCLE_UPDATE: (
        (
            _f("pose", "PoseStamped", "robot pose, in behavior_server's local frame"),
            _f("elapsed", FLOAT, "time since on_run succeeded [s]"),
            _f("costmap", "Costmap", "the local costmap, present only when changed", False),
        ),
        (
            *_BEHAVIOR_STATUS,
            _f(
                "cmd_vel",
                "TwistStamped",
                "the command to publish this cycle; every component finite; absent: none "
                "(the plugin stops the robot when the status is not 'running')",
                False,
            ),
            _f(
                "feedback",
                PARAMS,
                "the action's feedback fields, e.g. distance_traveled [m]; absent when none",
                False,
            ),
        ),
    ),
    Op.ON_ACTION_COMPLETION: (
        (
            _f("status", STR, "how the action ended: 'succeeded', 'failed' or 'cancelled'"),
            _f("elapsed", FLOAT, "the action's total_elapsed_time [s]"),
        ),
        (),
    ),
    Op.FIND_PLAN_SEGMENT: (
        (_f("pose", "PoseStamped", "robot pose, in the plan's frame"),),
        (
            _f("start", UINT, "first pose of the segment: an index into the plan set_plan sent"),
            _f("end", UINT, "one past its last pose; start < end <= the plan's length"),
        ),
    ),
}


class Timeout(str, Enum):
    """Which of a plugin's timeouts (and of a host's deadlines) bounds an op: the values are
    the parameter names of both (PROTOCOL.md section 8)."""

    CALL = "call"  # the control loop's: below the controller period
    LIFECYCLE = "lifecycle"
    CONFIGURE = "configure"  # imports, JIT compilation
    PLAN = "plan"  # create_plan and smooth may take seconds


#: Each op's timeout class: the one table the Python client, the C++ client (generated into
#: ops.hpp) and the host's deadlines read. ``reset`` is a control-loop call for every plugin
#: type: Nav2 calls it after every goal, and an abort must not wait on it.
OP_TIMEOUT: dict[Op, Timeout] = {
    Op.CONFIGURE: Timeout.CONFIGURE,
    Op.ACTIVATE: Timeout.LIFECYCLE,
    Op.DEACTIVATE: Timeout.LIFECYCLE,
    Op.CLEANUP: Timeout.LIFECYCLE,
    Op.SET_PARAMETERS: Timeout.LIFECYCLE,
    Op.SET_PLAN: Timeout.CALL,
    Op.COMPUTE_VELOCITY_COMMANDS: Timeout.CALL,
    Op.SET_SPEED_LIMIT: Timeout.CALL,
    Op.CANCEL: Timeout.CALL,
    Op.RESET: Timeout.CALL,
    Op.CREATE_PLAN: Timeout.PLAN,
    Op.CANCEL_PLAN: Timeout.LIFECYCLE,
    Op.SMOOTH: Timeout.PLAN,
    Op.IS_GOAL_REACHED: Timeout.CALL,
    Op.GET_TOLERANCES: Timeout.CALL,
    Op.CHECK: Timeout.CALL,
    Op.UPDATE_BOUNDS: Timeout.CALL,
    Op.UPDATE_COSTS: Timeout.CALL,
    Op.MATCH_SIZE: Timeout.CALL,
    # a behaviour: the goal's start and end as lifecycle calls, every cycle (behavior_server's
    # 10 Hz) a control-loop one
    Op.ON_RUN: Timeout.LIFECYCLE,
    Op.ON_CYCLE_UPDATE: Timeout.CALL,
    Op.ON_ACTION_COMPLETION: Timeout.LIFECYCLE,
    Op.FIND_PLAN_SEGMENT: Timeout.CALL,  # every control cycle
}

#: smooth gives the smoother ``max_time``: a client awaits the reply that long and this much
#: more [s], or its plan timeout when that is longer.
SMOOTH_GRACE_S: Final = 1.0


class CostmapSent(str, Enum):
    """Whether an op's request carries the plugin's costmap (PROTOCOL.md section 5)."""

    NEVER = "never"
    IF_CHANGED = "if_changed"  # when its version is not the one this session last delivered
    ALWAYS = "always"  # configure: a new session starts from the whole costmap


def _costmap_sent(op: Op) -> CostmapSent:
    field = next((f for f in BODIES[op][0] if f.name == "costmap"), None)
    if field is None:
        return CostmapSent.NEVER
    return CostmapSent.ALWAYS if field.required else CostmapSent.IF_CHANGED


#: Each op's costmap rule, read from its request's ``costmap`` field: required -> always,
#: optional -> when changed, none -> never. Both clients attach the costmap by this table
#: (the C++ one generated into ops.hpp); no call site says it.
COSTMAP_SENT: dict[Op, CostmapSent] = {op: _costmap_sent(op) for op in Op}

#: What a new session on the host (a restarted host, another replica: SessionUnknown) is sent
#: again right after configure (and activate, when active), per plugin type and in this order:
#: what the planner was told since configure that it cannot do without. Each client re-sends
#: it from its own state (the latest plan and goal; the speed limit in force; the behaviour's
#: action under way, until on_action_completion) and nothing else.
RESTORED: dict[PluginType, tuple[Op, ...]] = {
    PluginType.CONTROLLER: (Op.SET_PLAN, Op.SET_SPEED_LIMIT),
    PluginType.BEHAVIOR: (Op.ON_RUN,),
    PluginType.PATH_HANDLER: (Op.SET_PLAN,),
}

#: The control cycle in fewer queries (PROTOCOL.md section 15): op -> the ops its request may
#: carry. Nav2's controller_server calls the goal check, the progress check and the command
#: in one of two orders (goal check first or last); a call carries those that follow it.
# Lyrical's path handler cuts the cycle's plan between the check and the command: its
# find_plan_segment rides with the checks (section 19).
CARRIES: dict[Op, tuple[Op, ...]] = {
    Op.IS_GOAL_REACHED: (Op.CHECK, Op.FIND_PLAN_SEGMENT, Op.COMPUTE_VELOCITY_COMMANDS),
    Op.CHECK: (Op.FIND_PLAN_SEGMENT, Op.COMPUTE_VELOCITY_COMMANDS),
    Op.COMPUTE_VELOCITY_COMMANDS: (Op.IS_GOAL_REACHED,),
}

#: After a successful reply of op, whether Nav2 goes on to the next call of the cycle:
#: (reply field, the value it must have). An op not here goes on whenever it succeeds.
GOES_ON: dict[Op, tuple[str, bool]] = {
    Op.IS_GOAL_REACHED: ("reached", False),  # reached: controller_server stops
    Op.CHECK: ("making_progress", True),  # no progress: FailedToMakeProgress
}
