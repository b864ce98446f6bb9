"""Names shared by every party of the protocol: version, operations, plugin and error types."""

from __future__ import annotations

from enum import Enum

#: Sent in every request and reply; a host answers a different version with VersionMismatch.
PROTOCOL_VERSION = 1


class PluginType(str, Enum):
    CONTROLLER = "controller"
    GLOBAL_PLANNER = "global_planner"


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


LIFECYCLE_OPS = frozenset({Op.CONFIGURE, Op.ACTIVATE, Op.DEACTIVATE, Op.CLEANUP, Op.SET_PARAMETERS})
CONTROLLER_OPS = LIFECYCLE_OPS | {
    Op.SET_PLAN,
    Op.COMPUTE_VELOCITY_COMMANDS,
    Op.SET_SPEED_LIMIT,
    Op.CANCEL,
    Op.RESET,
}
GLOBAL_PLANNER_OPS = LIFECYCLE_OPS | {Op.CREATE_PLAN, Op.CANCEL_PLAN}
OPS_BY_PLUGIN = {
    PluginType.CONTROLLER: CONTROLLER_OPS,
    PluginType.GLOBAL_PLANNER: GLOBAL_PLANNER_OPS,
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
PROTOCOL_ERRORS = frozenset(
    {
        ErrorType.SESSION_UNKNOWN,
        ErrorType.VERSION_MISMATCH,
        ErrorType.BAD_REQUEST,
        ErrorType.UNAVAILABLE,
    }
)
