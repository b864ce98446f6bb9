"""What every planner gets from the host: name, frames, logger, parameters, the costmap."""

from __future__ import annotations

import logging
from abc import ABC
from typing import ClassVar

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif._context import PluginContext
from nav2_pyif.costmap import Costmap
from nav2_pyif.params import Parameters, ParamValue


class PlannerPlugin(ABC):
    """Base of Controller and GlobalPlanner. Subclasses need a constructor without arguments;
    set-up that needs parameters or the costmap belongs in ``configure``."""

    plugin_type: ClassVar[PluginType]
    _context: PluginContext

    def _attach(self, context: PluginContext) -> None:
        self._context = context

    @property
    def name(self) -> str:
        """The plugin name in Nav2 (e.g. ``FollowPath``)."""
        return self._context.name

    @property
    def node_name(self) -> str:
        return self._context.node_name

    @property
    def global_frame(self) -> str:
        """The costmap's global frame: poses, plans and the costmap are all in it."""
        return self._context.global_frame

    @property
    def robot_base_frame(self) -> str:
        return self._context.robot_base_frame

    @property
    def costmap(self) -> Costmap:
        """The latest costmap (replaced when Nav2's changes; never modify it)."""
        return self._context.costmap

    @property
    def params(self) -> Parameters:
        return self._context.params

    @property
    def nav2_params(self) -> dict[str, ParamValue]:
        """Nav2's parameters outside the plugin's namespace, by their Nav2 names, where the
        plugin knows them: ``controller_frequency`` [Hz] (see ``Controller.control_period``),
        ``inflation_radius`` [m] and ``cost_scaling_factor`` [1/m] (the costmap's inflation
        layer: also ``self.costmap.inflation``). Empty from plugins older than this field."""
        return self._context.nav2_params

    @property
    def logger(self) -> logging.Logger:
        return self._context.logger

    # --- lifecycle (nav2_core names, snake_case) -----------------------------------------
    def configure(self) -> None:
        """Declare parameters and allocate. Raise to fail Nav2's configure."""

    def activate(self) -> None:
        """Called when Nav2 activates the plugin."""

    def deactivate(self) -> None:
        """Called when Nav2 deactivates the plugin."""

    def cleanup(self) -> None:
        """Release resources; the session ends after this."""

    def on_parameters_changed(self, changed: dict[str, ParamValue]) -> None:
        """Called after ``ros2 param set`` changed accepted parameters (already in params)."""
