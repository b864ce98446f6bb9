"""Short names the runner accepts for the reference planners (nav2_pyif_planners). Only their
import paths: the runner never imports a planner; the planner host it starts does."""

ALIASES = {
    "astar": "nav2_pyif_planners.astar:AStar",
    "pure_pursuit": "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
    "mppi": "nav2_pyif_planners.mppi:MPPI",
    "mppi_jax": "nav2_pyif_planners.mppi_jax:MPPIJax",
    "mppi_nav2": "nav2_pyif_planners.mppi_nav2:Nav2MPPI",  # Nav2 MPPI (Jazzy) in JAX
    "learned": "nav2_pyif_planners.learned.controller:LearnedController",  # needs --scan
    "apf": "nav2_pyif_planners.apf",  # function-delegate style: its functions are the roles
    # Nav2's other plugins (--smoother, --goal-checker, --progress-checker, --layer, --recovery)
    "simple_smoother": "nav2_pyif_planners.simple_smoother:SimpleSmoother",
    "stopped_goal_checker": "nav2_pyif_planners.checker_plugins:StoppedGoalChecker",
    "simple_progress_checker": "nav2_pyif_planners.checker_plugins:SimpleProgressChecker",
    "keepout": "nav2_pyif_planners.keepout_layer:KeepOutLayer",
    "free_backup": "nav2_pyif_planners.free_backup:FreestBackUp",
}
