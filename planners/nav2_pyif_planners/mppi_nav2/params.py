"""The parameters of Nav2's MPPI controller (Jazzy, nav2_mppi_controller 1.3), by Nav2's names
and with Nav2's defaults, read from a planner's ``Parameters`` into hashable settings (the
jit-compiled step takes them as a static argument: a parameter change recompiles once).

A Nav2 YAML block arrives flattened the way ROS 2 flattens nested YAML: ``vx_max``,
``ConstraintCritic.cost_weight``, ``AckermannConstraints.min_turning_r``, ...
(``flatten`` does the same to a block read with PyYAML). Keys Nav2 has and this controller
cannot honour are read all the same, so they are not reported as misspelt, and each one set to
something other than its default is logged with a warning saying what happens instead.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml
from nav2_pyif import Parameters

#: Nav2 Jazzy's nav2_bringup FollowPath MPPI block, as a YAML file
NAV2_JAZZY_FILE = Path(__file__).with_name("nav2_jazzy.yaml")

#: Nav2's critic plugins this controller scores, in its names, with each critic's own
#: parameters and defaults (the critics' initialize() in nav2_mppi_controller/src/critics).
CRITIC_PARAMS: dict[str, dict[str, Any]] = {
    "ConstraintCritic": {"cost_power": 1, "cost_weight": 4.0},
    "CostCritic": {
        "cost_power": 1,
        "cost_weight": 3.81,
        "consider_footprint": False,
        "critical_cost": 300.0,
        "near_collision_cost": 253,
        "collision_cost": 1000000.0,
        "near_goal_distance": 0.5,
        "inflation_layer_name": "",
        "trajectory_point_step": 2,
    },
    "GoalCritic": {"cost_power": 1, "cost_weight": 5.0, "threshold_to_consider": 1.4},
    "GoalAngleCritic": {"cost_power": 1, "cost_weight": 3.0, "threshold_to_consider": 0.5},
    "ObstaclesCritic": {
        "cost_power": 1,
        "consider_footprint": False,
        "repulsion_weight": 1.5,
        "critical_weight": 20.0,
        "collision_cost": 100000.0,
        "collision_margin_distance": 0.10,
        "near_goal_distance": 0.5,
        "inflation_layer_name": "",
    },
    "PathAlignCritic": {
        "cost_power": 1,
        "cost_weight": 10.0,
        "max_path_occupancy_ratio": 0.07,
        "offset_from_furthest": 20,
        "trajectory_point_step": 4,
        "threshold_to_consider": 0.5,
        "use_path_orientations": False,
    },
    "PathAngleCritic": {
        "cost_power": 1,
        "cost_weight": 2.2,
        "offset_from_furthest": 4,
        "threshold_to_consider": 0.5,
        "max_angle_to_furthest": 0.785398,
        "mode": 0,
    },
    "PathFollowCritic": {
        "cost_power": 1,
        "cost_weight": 5.0,
        "offset_from_furthest": 6,
        "threshold_to_consider": 1.4,
    },
    "PreferForwardCritic": {"cost_power": 1, "cost_weight": 5.0, "threshold_to_consider": 0.5},
    "TwirlingCritic": {"cost_power": 1, "cost_weight": 10.0},
}

MOTION_MODELS = ("DiffDrive", "Omni", "Ackermann")
#: Lyrical's motion models are plugins: ``motion_model`` names a namespace whose ``plugin`` is
#: one of these classes (Nav2 1.5's nav2_bringup: ``motion_model: "diff_drive"`` and
#: ``diff_drive.plugin: "mppi::DiffDriveMotionModel"``).
MOTION_MODEL_PLUGINS = {f"mppi::{name}MotionModel": name for name in MOTION_MODELS}

#: Nav2 keys read but not honoured: name -> (default, what this controller does instead).
UNHONOURED: dict[str, tuple[Any, str]] = {
    "visualize": (False, "subscribe to the debug output local_plan instead"),
    "transform_tolerance": (0.1, "poses and the plan arrive in the costmap's frame"),
    "enforce_path_inversion": (False, "the plan is followed to its end, cusps included"),
    "inversion_xy_tolerance": (0.2, "enforce_path_inversion is not supported"),
    "inversion_yaw_tolerance": (0.4, "enforce_path_inversion is not supported"),
    "TrajectoryVisualizer.trajectory_step": (5, "no candidate trajectories are drawn"),
    "TrajectoryVisualizer.time_step": (3, "local_plan has every step"),
}


@dataclass(frozen=True)
class Critic:
    """One critic's settings: its Nav2 name, whether enabled, and its parameters."""

    name: str
    enabled: bool
    values: tuple[tuple[str, Any], ...]

    def __getitem__(self, key: str) -> Any:
        return dict(self.values)[key]


@dataclass(frozen=True)
class Settings:
    """Everything the compiled step needs that does not change cycle to cycle."""

    model_dt: float
    time_steps: int
    batch_size: int
    iteration_count: int
    temperature: float
    gamma: float
    vx_max: float
    vx_min: float
    vy_max: float
    wz_max: float
    ax_max: float
    ax_min: float
    ay_max: float
    ay_min: float
    az_max: float
    vx_std: float
    vy_std: float
    wz_std: float
    motion_model: str
    min_turning_r: float
    critics: tuple[Critic, ...]
    shift_control_sequence: bool
    # the costmap's side of the critics (Nav2 asks its Costmap2DROS for these)
    track_unknown_space: bool
    path_points: int  # the pruned plan's points, padded or subsampled to this (one shape)

    @property
    def holonomic(self) -> bool:
        return self.motion_model == "Omni"

    def critic(self, name: str) -> Critic | None:
        """The named critic when it is listed in ``critics`` and enabled."""
        for critic in self.critics:
            if critic.name == name and critic.enabled:
                return critic
        return None


def flatten(block: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """A Nav2 YAML block (nested mappings) -> ROS 2 parameter names with dots, as the
    controller server declares them: ``{"GoalCritic": {"cost_weight": 5.0}}`` ->
    ``{"GoalCritic.cost_weight": 5.0}``."""
    out: dict[str, Any] = {}
    for key, value in block.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(flatten(value, name + "."))
        else:
            out[name] = value
    return out


def nav2_jazzy_params(**overrides: Any) -> dict[str, Any]:
    """Nav2 Jazzy's nav2_bringup FollowPath MPPI block as parameters, ``overrides`` applied
    (e.g. ``batch_size=1000``)."""
    return {**flatten(yaml.safe_load(NAV2_JAZZY_FILE.read_text())), **overrides}


def _motion_model(p: Parameters) -> str:
    """DiffDrive, Omni or Ackermann, named as Jazzy's Nav2 names it (``motion_model:
    DiffDrive``) or as Lyrical's does (a namespace whose ``plugin`` is the model's class).
    Raises ValueError for a model Nav2 would not load."""
    name = p.declare(
        "motion_model",
        "DiffDrive",
        "DiffDrive, Omni or Ackermann; or (Lyrical) a namespace whose plugin is "
        "mppi::DiffDriveMotionModel, mppi::OmniMotionModel or mppi::AckermannMotionModel",
    )
    if name in MOTION_MODELS:
        return name
    plugin = p.get(f"{name}.plugin")
    if plugin in MOTION_MODEL_PLUGINS:
        return MOTION_MODEL_PLUGINS[plugin]
    if plugin is None:
        raise ValueError(
            f"Model {name} is not valid! Valid options are DiffDrive, Omni, or Ackermann, or a "
            f"namespace with a plugin ({name}.plugin: mppi::DiffDriveMotionModel, ...)"
        )
    raise ValueError(
        f"Failed to load motion model plugin '{name}': {plugin} is not one of "
        + ", ".join(MOTION_MODEL_PLUGINS)
    )


def read_settings(
    p: Parameters,
    controller_frequency: float | None,
    logger: logging.Logger,
    footprint: bool = False,
) -> Settings:
    """The controller's settings from its parameters (Nav2's names and defaults), with
    Nav2's corrections (ax_max made positive, ax_min and ay_min negative) and its checks.
    ``footprint``: the costmap has a footprint polygon (not a robot_radius); the critics'
    ``consider_footprint`` then defaults to true, the setting Nav2 finds consistent with it
    (Nav2's default false suits its bringup's round robot, and warns for any other).
    Raises ValueError for what Nav2 refuses at configure (an unknown motion model or critic
    mode, a control period longer than model_dt)."""
    dt = p.declare("model_dt", 0.05, "[s] per step of the horizon")
    values: dict[str, Any] = {
        "model_dt": dt,
        "time_steps": p.declare("time_steps", 56, "steps per rollout"),
        "batch_size": p.declare("batch_size", 1000, "rollouts per iteration"),
        "iteration_count": p.declare("iteration_count", 1, "optimisation iterations per cycle"),
        "temperature": p.declare("temperature", 0.3, "softmax selectiveness"),
        "gamma": p.declare("gamma", 0.015, "control cost trade-off"),
        "vx_max": p.declare("vx_max", 0.5, "[m/s]"),
        "vx_min": p.declare("vx_min", -0.35, "[m/s] negative: reversing allowed"),
        "vy_max": p.declare("vy_max", 0.5, "[m/s] Omni"),
        "wz_max": p.declare("wz_max", 1.9, "[rad/s]"),
        "ax_max": abs(p.declare("ax_max", 3.0, "[m/s^2] accelerating forward")),
        "ax_min": p.declare("ax_min", -3.0, "[m/s^2] decelerating"),
        "ay_max": p.declare("ay_max", 3.0, "[m/s^2] Omni"),
        "ay_min": p.declare("ay_min", -3.0, "[m/s^2] Omni"),
        "az_max": p.declare("az_max", 3.5, "[rad/s^2]"),
        "vx_std": p.declare("vx_std", 0.2, "[m/s] sampling sigma"),
        "vy_std": p.declare("vy_std", 0.2, "[m/s] sampling sigma"),
        "wz_std": p.declare("wz_std", 0.4, "[rad/s] sampling sigma"),
        "motion_model": _motion_model(p),
        "min_turning_r": p.declare("AckermannConstraints.min_turning_r", 0.2, "[m] Ackermann"),
        "track_unknown_space": p.declare(
            "track_unknown_space",
            False,
            "the local costmap's track_unknown_space: unknown cells are free, not collisions",
        ),
        "path_points": p.declare(
            "path_points", 0, "pruned plan points the step holds (0: from prune_distance)"
        ),
    }
    for name in ("ax_min", "ay_min"):
        if values[name] > 0.0:
            logger.warning(
                "Sign of the parameter %s is incorrect, consider setting it negative.", name
            )
            values[name] = -values[name]
    values["shift_control_sequence"] = _shift(dt, controller_frequency, logger)
    names = p.declare(
        "critics",
        ["ConstraintCritic", "CostCritic", "GoalCritic", "GoalAngleCritic", "PathAlignCritic",
         "PathFollowCritic", "PathAngleCritic", "PreferForwardCritic"],
        "critic plugins, Nav2's names (mppi::critics:: may be left out)",
    )  # fmt: skip
    values["critics"] = tuple(_critic(p, name, logger, footprint) for name in names)
    _warn_unhonoured(p, logger)
    return Settings(**values)


def _shift(dt: float, controller_frequency: float | None, logger: logging.Logger) -> bool:
    """Nav2's setOffset: the control sequence shifts by one step per cycle when the control
    period equals model_dt; a longer period is refused."""
    if not controller_frequency:
        logger.info("controller_frequency unknown: assuming a control period of model_dt")
        return True
    period = 1.0 / controller_frequency
    if period + 1e-6 < dt:
        logger.warning("Controller period is less then model dt, consider setting it equal")
        return False
    if abs(period - dt) < 1e-6:
        return True
    raise ValueError("Controller period more then model dt, set it equal to model dt")


def _critic(p: Parameters, name: str, logger: logging.Logger, footprint: bool) -> Critic:
    short = name.removeprefix("mppi::critics::")
    if short not in CRITIC_PARAMS:
        logger.warning(
            "critic %s is not implemented by this controller and is left out (it scores: %s)",
            name, ", ".join(CRITIC_PARAMS),
        )  # fmt: skip
        return Critic(short, False, ())
    enabled = p.declare(f"{short}.enabled", True, f"score with {short}")
    defaults = dict(CRITIC_PARAMS[short])
    if "consider_footprint" in defaults:
        defaults["consider_footprint"] = footprint
    values = tuple((key, p.declare(f"{short}.{key}", default)) for key, default in defaults.items())
    critic = Critic(short, enabled, values)
    if short == "PathAngleCritic" and critic["mode"] not in (0, 1, 2):
        raise ValueError(f"PathAngleCritic.mode {critic['mode']}: Invalid path angle mode!")
    return critic


def _warn_unhonoured(p: Parameters, logger: logging.Logger) -> None:
    for name, (default, instead) in UNHONOURED.items():
        value = p.declare(name, default, f"Nav2's; not honoured here: {instead}")
        if value != default:
            logger.warning("Nav2 parameter %s=%r is not honoured here: %s", name, value, instead)
