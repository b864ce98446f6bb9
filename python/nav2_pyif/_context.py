"""What the host keeps for each planner it serves and a planner reads through its properties
(``self.costmap``, ``self.params``, ``self.logger``, ...): the host's side of
``PlannerPlugin``, not the authors' API."""

from __future__ import annotations

import logging

from nav2_pyif.costmap import Costmap, Inflation
from nav2_pyif.debug import DebugOutputs
from nav2_pyif.inputs import Inputs
from nav2_pyif.params import Parameters, ParamValue


class PluginContext:
    """Per-session state the host keeps up to date (the costmap changes between calls)."""

    def __init__(
        self,
        name: str,
        node_name: str,
        global_frame: str,
        robot_base_frame: str,
        costmap: Costmap,
        params: Parameters,
        logger: logging.Logger,
        nav2_params: dict[str, ParamValue] | None = None,
    ) -> None:
        self.name = name
        self.node_name = node_name
        self.global_frame = global_frame
        self.robot_base_frame = robot_base_frame
        self.costmap = costmap
        self.params = params
        self.logger = logger
        # configure's nav2_params: controller_frequency, the inflation layer's parameters
        self.nav2_params: dict[str, ParamValue] = dict(nav2_params or {})
        self.inflation = Inflation.from_params(self.nav2_params)
        # a controller's extra inputs and debug outputs; set up at configure
        self.inputs = Inputs()
        self.debug = DebugOutputs({})
