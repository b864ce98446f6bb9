"""nav2_pyif: write Nav2 controllers, global planners, path smoothers, goal checkers,
progress checkers, costmap layers, behaviours and (Lyrical) path handlers in Python; serve them
over Zenoh.

The planner API (what a planner imports)::

    from nav2_pyif import Controller, GlobalPlanner, Costmap, Plan, GoalTolerances
    from nav2_pyif import Smoother, GoalChecker, ProgressChecker, CostmapLayer
    from nav2_pyif import Behavior, Status, Step, Failure  # behavior_server's plugins
    from nav2_pyif import PathHandler  # Lyrical's controller_server: the cycle's plan segment
    from nav2_pyif import NoValidControl, NoValidPathCouldBeFound, ...  # nav2_core names
    from nav2_pyif import carrot, pose_xy_yaw, wrap, ...  # geometry (nav2_pyif.geometry)
    from nav2_pyif import Batch, one_cycle  # many robots' cycles in one call (nav2_pyif.batch)
"""

from nav2_pyif.batch import Batch, one_cycle
from nav2_pyif.behavior import Behavior, Command, Failure, Status, Step, arc
from nav2_pyif.controller import Controller
from nav2_pyif.costmap import Costmap, Inflation
from nav2_pyif.costmap_layer import Combine, CostmapLayer, LayerWindow
from nav2_pyif.exceptions import (
    ControllerException,
    ControllerTFError,
    ControllerTimedOut,
    FailedToMakeProgress,
    FailedToSmoothPath,
    GoalOccupied,
    GoalOutsideMapBounds,
    InvalidController,
    InvalidPath,
    InvalidPlanner,
    InvalidSmoother,
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
    SmoothedPathInCollision,
    SmootherException,
    SmootherTimedOut,
    StartOccupied,
    StartOutsideMapBounds,
)
from nav2_pyif.geometry import (
    carrot,
    closest_index,
    limit_speed,
    path_length,
    path_xy_yaw,
    point_at_distance,
    pose_xy_yaw,
    quaternion_to_yaw,
    remaining_length,
    wrap,
    yaw_of,
    yaw_to_quaternion,
)
from nav2_pyif.global_planner import GlobalPlanner
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.params import Parameters, ParamValue
from nav2_pyif.path_handler import PathHandler
from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin
from nav2_pyif.progress_checker import ProgressChecker
from nav2_pyif.smoother import Smoother

__version__ = "0.1.0"

__all__ = [
    "Batch",
    "Behavior",
    "Combine",
    "Command",
    "Controller",
    "ControllerException",
    "ControllerTFError",
    "ControllerTimedOut",
    "Costmap",
    "CostmapLayer",
    "FailedToMakeProgress",
    "FailedToSmoothPath",
    "Failure",
    "GlobalPlanner",
    "GoalChecker",
    "GoalOccupied",
    "GoalOutsideMapBounds",
    "GoalTolerances",
    "Inflation",
    "InvalidController",
    "InvalidPath",
    "InvalidPlanner",
    "InvalidSmoother",
    "LayerWindow",
    "Nav2Error",
    "NoValidControl",
    "NoValidPathCouldBeFound",
    "NoViapointsGiven",
    "ParamValue",
    "Parameters",
    "PathHandler",
    "PatienceExceeded",
    "Plan",
    "PlannerCancelled",
    "PlannerException",
    "PlannerLoadError",
    "PlannerPlugin",
    "PlannerTFError",
    "PlannerTimedOut",
    "ProgressChecker",
    "SmoothedPathInCollision",
    "Smoother",
    "SmootherException",
    "SmootherTimedOut",
    "StartOccupied",
    "StartOutsideMapBounds",
    "Status",
    "Step",
    "arc",
    "carrot",
    "closest_index",
    "limit_speed",
    "one_cycle",
    "path_length",
    "path_xy_yaw",
    "point_at_distance",
    "pose_xy_yaw",
    "quaternion_to_yaw",
    "remaining_length",
    "wrap",
    "yaw_of",
    "yaw_to_quaternion",
]
