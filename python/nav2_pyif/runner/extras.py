"""The runner's other Nav2 plugins, each served by the planner host as in Nav2 and called where
Nav2 calls it: a costmap layer on the costmap before planning, a smoother between the planner
and the controller, a goal checker and a progress checker in every control cycle (in one query
with the controller's call when the host serves all three: PROTOCOL.md section 15)."""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
import zenoh

from nav2_pyif.client import (
    BehaviorClient,
    ControlCycle,
    ControllerClient,
    CostmapLayerClient,
    GoalCheckerClient,
    ProgressCheckerClient,
    SmootherClient,
    Timeouts,
)
from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.costmap import Costmap
from nav2_pyif.costmap_layer import LayerWindow
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.params import ParamValue

#: The plugin roles the runner takes besides the controller and the planner, their keys.
KEYS = {
    "smoother": "nav2_pyif/sim/simple_smoother",
    "goal_checker": "nav2_pyif/sim/goal_checker",
    "progress_checker": "nav2_pyif/sim/progress_checker",
    "layer": "nav2_pyif/sim/keepout",
    "recovery": "nav2_pyif/sim/backup",
}
CLIENTS: dict[str, Callable[..., PluginClient]] = {
    "smoother": SmootherClient,
    "goal_checker": GoalCheckerClient,
    "progress_checker": ProgressCheckerClient,
    "layer": CostmapLayerClient,
    "recovery": BehaviorClient,
}


@dataclass
class LayerEffect:
    """What the layer did to the global costmap, for the report and the picture."""

    cells: npt.NDArray[np.bool_]  # (size_y, size_x): cells whose cost the layer changed
    window: LayerWindow


@dataclass
class Extras:
    """The clients of the plugins a run asked for (roles absent when not asked for)."""

    clients: dict[str, PluginClient] = field(default_factory=dict)

    @property
    def smoother(self) -> SmootherClient | None:
        return self.clients.get("smoother")  # type: ignore[return-value]

    @property
    def goal_checker(self) -> GoalCheckerClient | None:
        return self.clients.get("goal_checker")  # type: ignore[return-value]

    @property
    def progress_checker(self) -> ProgressCheckerClient | None:
        return self.clients.get("progress_checker")  # type: ignore[return-value]

    @property
    def layer(self) -> CostmapLayerClient | None:
        return self.clients.get("layer")  # type: ignore[return-value]

    @property
    def recovery(self) -> BehaviorClient | None:
        return self.clients.get("recovery")  # type: ignore[return-value]

    def records(self) -> list[Any]:
        return [r for client in self.clients.values() for r in client.records or []]


@contextlib.contextmanager
def extra_clients(
    session: zenoh.Session,
    specs: dict[str, str],
    params: dict[str, dict[str, ParamValue]],
    costmap: Costmap,
    timeouts: Timeouts,
) -> Iterator[Extras]:
    """A client per role in ``specs`` (on its KEYS key), closed on exit."""
    extras = Extras()
    try:
        for role in specs:
            extras.clients[role] = CLIENTS[role](
                session,
                KEYS[role],
                costmap,
                timeouts=timeouts,
                params=params.get(role, {}),
                record_calls=True,
            )
        yield extras
    finally:
        for client in extras.clients.values():
            client.close()


def apply_layer(
    layer: CostmapLayerClient, costmap: Costmap, robot: tuple[float, float, float]
) -> tuple[Costmap, LayerEffect]:
    """One costmap update with the layer, as nav2_costmap_2d's LayeredCostmap makes it: the
    master's size (match_size), the bounds the layer wants updated (update_bounds, from none),
    its costs for the master's window covering them (update_costs), combined as it says."""
    layer.match_size(
        costmap.size_x, costmap.size_y, costmap.resolution, costmap.origin_x, costmap.origin_y
    )
    bounds = layer.update_bounds(robot, (math.inf, math.inf, -math.inf, -math.inf))
    window = _cells_of(bounds, costmap)
    data = np.array(costmap.data, copy=True)
    if window.shape[0] > 0 and window.shape[1] > 0:
        costs, combine = layer.update_costs(window)
        rows, cols = slice(window.min_j, window.max_j), slice(window.min_i, window.max_i)
        data[rows, cols] = combine.apply(data[rows, cols], costs)
    updated = costmap.with_costs(data, costmap.version + 1)
    return updated, LayerEffect(data != costmap.data, window)


def _cells_of(bounds: tuple[float, float, float, float], costmap: Costmap) -> LayerWindow:
    """The master's cells covering ``bounds`` (clipped to the map; empty when they are)."""
    min_x, min_y, max_x, max_y = bounds
    res = costmap.resolution

    def cell(value: float, origin: float, size: int, up: bool) -> int:
        if not math.isfinite(value):
            return size if value > 0 else 0
        index = (value - origin) / res
        return int(np.clip(math.ceil(index) if up else math.floor(index), 0, size))

    i0 = cell(min_x, costmap.origin_x, costmap.size_x, False)
    j0 = cell(min_y, costmap.origin_y, costmap.size_y, False)
    i1 = max(i0, cell(max_x, costmap.origin_x, costmap.size_x, True))
    j1 = max(j0, cell(max_y, costmap.origin_y, costmap.size_y, True))
    return LayerWindow(i0, j0, i1, j1, costmap.origin_x, costmap.origin_y, res)


#: What a cycle's controller call carries besides pose and velocity: the new input messages
#: (name -> (message, receive time [ns])) and the debug outputs asked for.
Sensed = tuple[dict[str, tuple[Any, int]], list[str]]


class CycleCalls:
    """One control cycle's calls in Nav2's order (controller_server's computeControl, the goal
    check first as in Jazzy from 1.3.13): the goal check, the progress check, the command;
    with Python checkers through ControlCycle."""

    def __init__(
        self, controller: ControllerClient, extras: Extras, tolerances: GoalTolerances
    ) -> None:
        self.controller = controller
        self.extras = extras
        self.tolerances = tolerances
        self.cycle: ControlCycle | None = None
        if extras.goal_checker is not None:
            self.cycle = ControlCycle(controller, extras.goal_checker, extras.progress_checker)

    def start(self) -> None:
        """A new goal: the checkers reset (Nav2 does so on every FollowPath goal); the
        controller gets the Python goal checker's tolerances."""
        for checker in (self.extras.goal_checker, self.extras.progress_checker):
            if checker is not None:
                checker.reset()
        if self.extras.goal_checker is not None:
            self.tolerances = self.extras.goal_checker.get_tolerances() or self.tolerances

    def goal_reached(self, pose: Any, goal: Any, velocity: Any, sensed: Sensed) -> bool | None:
        """The Python goal checker's answer; None without one (the runner checks itself)."""
        if self.cycle is None:
            return None
        return self.cycle.is_goal_reached(pose, goal.pose, velocity, self.tolerances, *sensed)

    def making_progress(self, pose: Any) -> bool:
        if self.cycle is not None and self.cycle.progress_checker is not None:
            return self.cycle.check(pose)
        checker = self.extras.progress_checker
        return True if checker is None else checker.check(pose)

    def compute(self, pose: Any, velocity: Any, sensed: Sensed) -> Any:
        if self.cycle is not None:
            return self.cycle.compute_velocity_commands(pose, velocity, self.tolerances, *sensed)
        return self.controller.compute_velocity_commands(pose, velocity, self.tolerances, *sensed)

    @property
    def carried(self) -> tuple[int, int]:
        """(calls answered from a carried reply, calls sent on their own)."""
        return (self.cycle.carried_used, self.cycle.sent_alone) if self.cycle else (0, 0)
