"""Names shared by every party of the protocol: version, operations, plugin and error types,
a behaviour's status and failure names."""

from __future__ import annotations

from enum import Enum

#: Sent in every request and reply; a host answers a different version with VersionMismatch.
PROTOCOL_VERSION = 2

#: The input names (a controller's ``inputs`` parameter) one session may send: the host keeps
#: the latest message of each, so a session's memory is bounded by them.
MAX_INPUTS = 64


class PluginType(str, Enum):
    CONTROLLER = "controller"
    GLOBAL_PLANNER = "global_planner"
    SMOOTHER = "smoother"  # nav2_core::Smoother (smoother_server)
    GOAL_CHECKER = "goal_checker"  # nav2_core::GoalChecker (controller_server)
    PROGRESS_CHECKER = "progress_checker"  # nav2_core::ProgressChecker (controller_server)
    COSTMAP_LAYER = "costmap_layer"  # nav2_costmap_2d::Layer (a costmap's plugins)
    BEHAVIOR = "behavior"  # nav2_core::Behavior (behavior_server), as TimedBehavior runs it
    PATH_HANDLER = "path_handler"  # nav2_core::PathHandler (controller_server, Lyrical)


class Op(str, Enum):
    """Every operation. The value is the last chunk of the request key."""

    CONFIGURE = "configure"
    ACTIVATE = "activate"
    DEACTIVATE = "deactivate"
    CLEANUP = "cleanup"
    SET_PARAMETERS = "set_parameters"
    # controller
    SET_PLAN = "set_plan"
    COMPUTE_VELOCITY_COMMANDS = "compute_velocity_commands"
    SET_SPEED_LIMIT = "set_speed_limit"
    CANCEL = "cancel"
    RESET = "reset"
    # global planner
    CREATE_PLAN = "create_plan"
    CANCEL_PLAN = "cancel_plan"
    # smoother
    SMOOTH = "smooth"
    # goal checker (and RESET)
    IS_GOAL_REACHED = "is_goal_reached"
    GET_TOLERANCES = "get_tolerances"
    # progress checker (and RESET)
    CHECK = "check"
    # costmap layer (and RESET)
    UPDATE_BOUNDS = "update_bounds"
    UPDATE_COSTS = "update_costs"
    MATCH_SIZE = "match_size"
    # behavior (nav2_behaviors::TimedBehavior's hooks)
    ON_RUN = "on_run"
    ON_CYCLE_UPDATE = "on_cycle_update"
    ON_ACTION_COMPLETION = "on_action_completion"
    # path handler (and SET_PLAN): Lyrical's nav2_core::PathHandler
    FIND_PLAN_SEGMENT = "find_plan_segment"


LIFECYCLE_OPS = frozenset({Op.CONFIGURE, Op.ACTIVATE, Op.DEACTIVATE, Op.CLEANUP, Op.SET_PARAMETERS})
CONTROLLER_OPS = LIFECYCLE_OPS | {
    Op.SET_PLAN,
    Op.COMPUTE_VELOCITY_COMMANDS,
    Op.SET_SPEED_LIMIT,
    Op.CANCEL,
    Op.RESET,
}
GLOBAL_PLANNER_OPS = LIFECYCLE_OPS | {Op.CREATE_PLAN, Op.CANCEL_PLAN}
SMOOTHER_OPS = LIFECYCLE_OPS | {Op.SMOOTH}
# Nav2's checkers have no activate/deactivate/cleanup (only initialize and reset); their
# plugins still send configure (= initialize) and cleanup (when destroyed), and the lifecycle
# ops are accepted so that one session machinery serves every plugin type.
GOAL_CHECKER_OPS = LIFECYCLE_OPS | {Op.IS_GOAL_REACHED, Op.GET_TOLERANCES, Op.RESET}
PROGRESS_CHECKER_OPS = LIFECYCLE_OPS | {Op.CHECK, Op.RESET}
COSTMAP_LAYER_OPS = LIFECYCLE_OPS | {Op.UPDATE_BOUNDS, Op.UPDATE_COSTS, Op.MATCH_SIZE, Op.RESET}
BEHAVIOR_OPS = LIFECYCLE_OPS | {Op.ON_RUN, Op.ON_CYCLE_UPDATE, Op.ON_ACTION_COMPLETION}
# Like the checkers, a path handler has only initialize in Nav2 (configure here).
PATH_HANDLER_OPS = LIFECYCLE_OPS | {Op.SET_PLAN, Op.FIND_PLAN_SEGMENT}
OPS_BY_PLUGIN = {
    PluginType.CONTROLLER: CONTROLLER_OPS,
    PluginType.GLOBAL_PLANNER: GLOBAL_PLANNER_OPS,
    PluginType.SMOOTHER: SMOOTHER_OPS,
    PluginType.GOAL_CHECKER: GOAL_CHECKER_OPS,
    PluginType.PROGRESS_CHECKER: PROGRESS_CHECKER_OPS,
    PluginType.COSTMAP_LAYER: COSTMAP_LAYER_OPS,
    PluginType.BEHAVIOR: BEHAVIOR_OPS,
    PluginType.PATH_HANDLER: PATH_HANDLER_OPS,
}


class ErrorType(str, Enum):
    """The ``error.type`` of a failed reply: nav2_core exception names, then protocol errors."""

    # nav2_core controller exceptions (Jazzy+; Humble maps all of them to PlannerException)
    CONTROLLER_EXCEPTION = "ControllerException"
    INVALID_CONTROLLER = "InvalidController"
    CONTROLLER_TF_ERROR = "ControllerTFError"
    FAILED_TO_MAKE_PROGRESS = "FailedToMakeProgress"
    PATIENCE_EXCEEDED = "PatienceExceeded"
    INVALID_PATH = "InvalidPath"
    NO_VALID_CONTROL = "NoValidControl"
    CONTROLLER_TIMED_OUT = "ControllerTimedOut"
    # nav2_core planner exceptions
    PLANNER_EXCEPTION = "PlannerException"
    INVALID_PLANNER = "InvalidPlanner"
    START_OCCUPIED = "StartOccupied"
    GOAL_OCCUPIED = "GoalOccupied"
    START_OUTSIDE_MAP_BOUNDS = "StartOutsideMapBounds"
    GOAL_OUTSIDE_MAP_BOUNDS = "GoalOutsideMapBounds"
    NO_VALID_PATH_COULD_BE_FOUND = "NoValidPathCouldBeFound"
    PLANNER_TIMED_OUT = "PlannerTimedOut"
    PLANNER_TF_ERROR = "PlannerTFError"
    NO_VIAPOINTS_GIVEN = "NoViapointsGiven"
    PLANNER_CANCELLED = "PlannerCancelled"
    # nav2_core smoother exceptions (Jazzy+; smoother_exceptions.hpp). InvalidPath is also a
    # smoother exception there: the plugin's kind decides which C++ class it becomes.
    SMOOTHER_EXCEPTION = "SmootherException"
    INVALID_SMOOTHER = "InvalidSmoother"
    SMOOTHER_TIMED_OUT = "SmootherTimedOut"
    SMOOTHED_PATH_IN_COLLISION = "SmoothedPathInCollision"
    FAILED_TO_SMOOTH_PATH = "FailedToSmoothPath"
    # protocol errors: not raised by planners
    SESSION_UNKNOWN = "SessionUnknown"
    VERSION_MISMATCH = "VersionMismatch"
    BAD_REQUEST = "BadRequest"
    UNAVAILABLE = "Unavailable"


CONTROLLER_ERRORS = frozenset(
    {
        ErrorType.CONTROLLER_EXCEPTION,
        ErrorType.INVALID_CONTROLLER,
        ErrorType.CONTROLLER_TF_ERROR,
        ErrorType.FAILED_TO_MAKE_PROGRESS,
        ErrorType.PATIENCE_EXCEEDED,
        ErrorType.INVALID_PATH,
        ErrorType.NO_VALID_CONTROL,
        ErrorType.CONTROLLER_TIMED_OUT,
    }
)
PLANNER_ERRORS = frozenset(
    {
        ErrorType.PLANNER_EXCEPTION,
        ErrorType.INVALID_PLANNER,
        ErrorType.START_OCCUPIED,
        ErrorType.GOAL_OCCUPIED,
        ErrorType.START_OUTSIDE_MAP_BOUNDS,
        ErrorType.GOAL_OUTSIDE_MAP_BOUNDS,
        ErrorType.NO_VALID_PATH_COULD_BE_FOUND,
        ErrorType.PLANNER_TIMED_OUT,
        ErrorType.PLANNER_TF_ERROR,
        ErrorType.NO_VIAPOINTS_GIVEN,
        ErrorType.PLANNER_CANCELLED,
    }
)
SMOOTHER_ERRORS = frozenset(
    {
        ErrorType.SMOOTHER_EXCEPTION,
        ErrorType.INVALID_SMOOTHER,
        ErrorType.INVALID_PATH,
        ErrorType.SMOOTHER_TIMED_OUT,
        ErrorType.SMOOTHED_PATH_IN_COLLISION,
        ErrorType.FAILED_TO_SMOOTH_PATH,
    }
)
#: The nav2_core exceptions a plugin of each type throws under their own name; any other
#: error type becomes that plugin type's generic exception (PROTOCOL.md section 7). Nav2 has
#: no checker exceptions: the checkers run inside controller_server's control loop, whose
#: ControllerException aborts the FollowPath action.
ERRORS_BY_PLUGIN = {
    PluginType.CONTROLLER: CONTROLLER_ERRORS,
    PluginType.GLOBAL_PLANNER: PLANNER_ERRORS,
    PluginType.SMOOTHER: SMOOTHER_ERRORS,
    PluginType.GOAL_CHECKER: frozenset({ErrorType.CONTROLLER_EXCEPTION}),
    PluginType.PROGRESS_CHECKER: frozenset({ErrorType.CONTROLLER_EXCEPTION}),
    # A layer never throws into Nav2 (its costmap's update thread would die): the plugin logs
    # the error and keeps its last costs. ControllerException only names the failure here.
    PluginType.COSTMAP_LAYER: frozenset({ErrorType.CONTROLLER_EXCEPTION}),
    # Nor does a behaviour: TimedBehavior ends its action with a status and an error code.
    # The plugin turns any failed call into FAILED (the action's UNKNOWN code);
    # ControllerException only names the failure here.
    PluginType.BEHAVIOR: frozenset({ErrorType.CONTROLLER_EXCEPTION}),
    # A path handler runs in controller_server's cycle and throws its exceptions, as Nav2's
    # FeasiblePathHandler does (InvalidPath, ControllerTFError).
    PluginType.PATH_HANDLER: CONTROLLER_ERRORS,
}
#: The catch-all exception of each plugin type, its host failure and its configure failure.
GENERIC_ERROR = {
    PluginType.CONTROLLER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.GLOBAL_PLANNER: ErrorType.PLANNER_EXCEPTION,
    PluginType.SMOOTHER: ErrorType.SMOOTHER_EXCEPTION,
    PluginType.GOAL_CHECKER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.PROGRESS_CHECKER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.COSTMAP_LAYER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.BEHAVIOR: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.PATH_HANDLER: ErrorType.CONTROLLER_EXCEPTION,
}
#: What a plugin throws when its host failed it rather than the planner: no host alive, no
#: reply in time, a broken connection, or an ``Unavailable`` reply (the worker crashed and is
#: restarting, or overran its deadline). Chosen so that Nav2's own behaviour-tree conditions
#: send the navigation to a recovery (RELIABILITY.md, "Which exception a host failure
#: becomes"): Jazzy, Kilted and Lyrical's WouldAControllerRecoveryHelp accepts
#: NO_VALID_CONTROL and UNKNOWN but not CONTROLLER_TIMED_OUT, and controller_server's
#: ``failure_tolerance`` holds the robot still and retries through NoValidControl only;
#: WouldAPlannerRecoveryHelp and WouldASmootherRecoveryHelp accept UNKNOWN (the generic
#: exceptions). On Humble every one of them is PlannerException, which its BT always recovers.
#: A planner's own typed errors (a planner raising ControllerTimedOut) pass through as raised.
HOST_FAILURE_ERROR = {
    **GENERIC_ERROR,  # UNKNOWN in every server: the generic exceptions are retried
    PluginType.CONTROLLER: ErrorType.NO_VALID_CONTROL,
    # the cycle's plan comes from it: a host failure is the controller's (held still, retried)
    PluginType.PATH_HANDLER: ErrorType.NO_VALID_CONTROL,
}
INVALID_ERROR = {
    PluginType.CONTROLLER: ErrorType.INVALID_CONTROLLER,
    PluginType.GLOBAL_PLANNER: ErrorType.INVALID_PLANNER,
    PluginType.SMOOTHER: ErrorType.INVALID_SMOOTHER,
    PluginType.GOAL_CHECKER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.PROGRESS_CHECKER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.COSTMAP_LAYER: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.BEHAVIOR: ErrorType.CONTROLLER_EXCEPTION,
    PluginType.PATH_HANDLER: ErrorType.INVALID_CONTROLLER,
}
PROTOCOL_ERRORS = frozenset(
    {
        ErrorType.SESSION_UNKNOWN,
        ErrorType.VERSION_MISMATCH,
        ErrorType.BAD_REQUEST,
        ErrorType.UNAVAILABLE,
    }
)


class BehaviorStatus(str, Enum):
    """TimedBehavior's Status (a behaviour's reply, PROTOCOL.md section 17)."""

    SUCCEEDED = "succeeded"
    FAILED = "failed"
    RUNNING = "running"


class BehaviorFailure(str, Enum):
    """Why a behaviour failed: the plugin sets the action result's error code of that name
    (BackUp's COLLISION_AHEAD, Spin's TIMEOUT, ...; UNKNOWN where the action has no such
    code, and none on Humble, whose behaviour results have no error code)."""

    NONE = ""
    UNKNOWN = "unknown"
    TIMEOUT = "timeout"
    TF_ERROR = "tf_error"
    INVALID_INPUT = "invalid_input"
    COLLISION_AHEAD = "collision_ahead"
