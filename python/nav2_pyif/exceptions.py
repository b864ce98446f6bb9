"""Exceptions with nav2_core's names. Raise them from a planner; the Nav2 plugin rethrows the
C++ exception of the same name, so the action fails with the matching error code.

Anything else a planner raises reaches Nav2 as the generic ControllerException or
PlannerException, its Python type and traceback in the message and the host's log.
"""

from __future__ import annotations

from typing import ClassVar

from nav2_pyif_protocol.constants import GENERIC_ERROR, HOST_FAILURE_ERROR, ErrorType, PluginType


class Nav2Error(Exception):
    """Base of every nav2_core-named exception. ``remote_traceback`` is set on the client side
    when the error came from a planner host; ``host_failed`` when the host, not its planner,
    failed the call (none alive, no reply in time, Unavailable)."""

    error_type: ClassVar[ErrorType]

    def __init__(
        self,
        message: str = "",
        *,
        remote_traceback: str = "",
        python_type: str = "",
        host_failed: bool = False,
    ):
        super().__init__(message)
        self.remote_traceback = remote_traceback
        self.python_type = python_type
        self.host_failed = host_failed


class ControllerException(Nav2Error):
    error_type = ErrorType.CONTROLLER_EXCEPTION


class InvalidController(ControllerException):
    error_type = ErrorType.INVALID_CONTROLLER


class ControllerTFError(ControllerException):
    error_type = ErrorType.CONTROLLER_TF_ERROR


class FailedToMakeProgress(ControllerException):
    error_type = ErrorType.FAILED_TO_MAKE_PROGRESS


class PatienceExceeded(ControllerException):
    error_type = ErrorType.PATIENCE_EXCEEDED


class NoValidControl(ControllerException):
    error_type = ErrorType.NO_VALID_CONTROL


class ControllerTimedOut(ControllerException):
    error_type = ErrorType.CONTROLLER_TIMED_OUT


class SmootherException(Nav2Error):
    error_type = ErrorType.SMOOTHER_EXCEPTION


class InvalidSmoother(SmootherException):
    error_type = ErrorType.INVALID_SMOOTHER


class SmootherTimedOut(SmootherException):
    error_type = ErrorType.SMOOTHER_TIMED_OUT


class SmoothedPathInCollision(SmootherException):
    error_type = ErrorType.SMOOTHED_PATH_IN_COLLISION


class FailedToSmoothPath(SmootherException):
    error_type = ErrorType.FAILED_TO_SMOOTH_PATH


class InvalidPath(ControllerException, SmootherException):
    """nav2_core has an InvalidPath among the controller exceptions and another among the
    smoother exceptions; this one is both, and the plugin's kind picks the C++ class."""

    error_type = ErrorType.INVALID_PATH


class PlannerException(Nav2Error):
    error_type = ErrorType.PLANNER_EXCEPTION


class InvalidPlanner(PlannerException):
    error_type = ErrorType.INVALID_PLANNER


class StartOccupied(PlannerException):
    error_type = ErrorType.START_OCCUPIED


class GoalOccupied(PlannerException):
    error_type = ErrorType.GOAL_OCCUPIED


class StartOutsideMapBounds(PlannerException):
    error_type = ErrorType.START_OUTSIDE_MAP_BOUNDS


class GoalOutsideMapBounds(PlannerException):
    error_type = ErrorType.GOAL_OUTSIDE_MAP_BOUNDS


class NoValidPathCouldBeFound(PlannerException):
    error_type = ErrorType.NO_VALID_PATH_COULD_BE_FOUND


class PlannerTimedOut(PlannerException):
    error_type = ErrorType.PLANNER_TIMED_OUT


class PlannerTFError(PlannerException):
    error_type = ErrorType.PLANNER_TF_ERROR


class NoViapointsGiven(PlannerException):
    error_type = ErrorType.NO_VIAPOINTS_GIVEN


class PlannerCancelled(PlannerException):
    error_type = ErrorType.PLANNER_CANCELLED


NAV2_EXCEPTIONS: dict[str, type[Nav2Error]] = {
    cls.error_type.value: cls
    for cls in (
        ControllerException,
        InvalidController,
        ControllerTFError,
        FailedToMakeProgress,
        PatienceExceeded,
        InvalidPath,
        NoValidControl,
        ControllerTimedOut,
        PlannerException,
        InvalidPlanner,
        StartOccupied,
        GoalOccupied,
        StartOutsideMapBounds,
        GoalOutsideMapBounds,
        NoValidPathCouldBeFound,
        PlannerTimedOut,
        PlannerTFError,
        NoViapointsGiven,
        PlannerCancelled,
        SmootherException,
        InvalidSmoother,
        SmootherTimedOut,
        SmoothedPathInCollision,
        FailedToSmoothPath,
    )
}


def generic_error(plugin_type: PluginType) -> type[Nav2Error]:
    """The catch-all nav2_core exception of a plugin type (ControllerException for the
    checkers: Nav2 has none of its own for them)."""
    return NAV2_EXCEPTIONS[GENERIC_ERROR[plugin_type].value]


def host_failure_error(plugin_type: PluginType) -> type[Nav2Error]:
    """What a plugin of this type raises when its host, not its planner, failed the call (none
    alive, no reply in time, Unavailable): the exception Nav2's recovery conditions retry
    (constants.HOST_FAILURE_ERROR)."""
    return NAV2_EXCEPTIONS[HOST_FAILURE_ERROR[plugin_type].value]


class PlannerLoadError(Exception):
    """A planner could not be imported or is not a planner (bad spec, import error, ...)."""
