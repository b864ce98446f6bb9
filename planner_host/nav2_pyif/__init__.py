"""nav2_pyif: write Nav2 controllers and global planners in Python; serve them over Zenoh.

The planner API (what a planner imports)::

    from nav2_pyif import Controller, GlobalPlanner, Costmap, Plan, GoalChecker
    from nav2_pyif import NoValidControl, NoValidPathCouldBeFound, ...  # nav2_core names
"""

from nav2_pyif.controller import Controller
from nav2_pyif.costmap import Costmap
from nav2_pyif.exceptions import (
    ControllerException,
    ControllerTFError,
    ControllerTimedOut,
    FailedToMakeProgress,
    GoalOccupied,
    GoalOutsideMapBounds,
    InvalidController,
    InvalidPath,
    InvalidPlanner,
    Nav2Error,
    NoValidControl,
    NoValidPathCouldBeFound,
    NoViapointsGiven,
    PatienceExceeded,
    PlannerCancelled,
    PlannerException,
    PlannerLoadError,
    PlannerTFError,
    PlannerTimedOut,
    StartOccupied,
    StartOutsideMapBounds,
)
from nav2_pyif.global_planner import GlobalPlanner
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.params import Parameters, ParamValue
from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin

__version__ = "0.1.0"

__all__ = [
    "Controller",
    "ControllerException",
    "ControllerTFError",
    "ControllerTimedOut",
    "Costmap",
    "FailedToMakeProgress",
    "GlobalPlanner",
    "GoalChecker",
    "GoalOccupied",
    "GoalOutsideMapBounds",
    "InvalidController",
    "InvalidPath",
    "InvalidPlanner",
    "Nav2Error",
    "NoValidControl",
    "NoValidPathCouldBeFound",
    "NoViapointsGiven",
    "ParamValue",
    "Parameters",
    "PatienceExceeded",
    "Plan",
    "PlannerCancelled",
    "PlannerException",
    "PlannerLoadError",
    "PlannerPlugin",
    "PlannerTFError",
    "PlannerTimedOut",
    "StartOccupied",
    "StartOutsideMapBounds",
]
