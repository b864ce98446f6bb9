"""OMPL's RRT* or PRM* (the extra ``ompl``) as a Nav2 global planner.

OMPL searches the plane (x, y) over the whole costmap. A state is valid where its cell costs
less than ``costmap.circumscribed_cost(margin=clearance)``: there the robot touches nothing at
any heading with ``clearance`` metres to spare, so the controller can follow the path whatever
the footprint (253, Nav2's "inscribed", is safe only for a round robot). The spare matters
because OMPL shortens its path until it grazes whatever it may not enter, and a controller
that cuts corners (pure pursuit) then grazes obstacles; near the start and the goal, where the
robot is or must be, the footprint alone is required. Nav2's cancel ends OMPL's solve through
its termination condition, within a few hundred state checks rather than at the end of the time
budget.

Why the cancel is asked in the validity checker and not given to OMPL as a Python termination
condition: PRM* evaluates its condition in a thread of its own while OMPL's Python binding holds
the GIL through ``solve``, and a Python condition there deadlocks at the solve's end (seen here
on the third plan or so). The checker runs in the thread that called ``solve``; the condition it
ends is OMPL's own, in C++.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from nav2_pyif import (
    Costmap,
    GlobalPlanner,
    GoalOccupied,
    InvalidPlanner,
    NoValidPathCouldBeFound,
    PlannerCancelled,
    StartOccupied,
    pose_xy_yaw,
)
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

ALGORITHMS = {"rrtstar": og.RRTstar, "prmstar": og.PRMstar}
CANCEL_EVERY = 256  # state checks between two looks at Nav2's cancel


class OMPLPlanner(GlobalPlanner):
    """Plans with OMPL in the costmap's frame; each pose faces the next, the last the goal."""

    def configure(self) -> None:
        self.algorithm = self.params.declare("algorithm", "rrtstar", "rrtstar or prmstar")
        self.max_time = self.params.declare("max_time", 0.5, "[s] OMPL's search for one plan")
        self.timeout = self.params.declare("timeout", 5.0, "[s] the search goes on for a path")
        self.clearance = self.params.declare(
            "clearance", 0.1, "[m] the path keeps this clear beyond the footprint"
        )
        if self.algorithm not in ALGORITHMS:
            raise InvalidPlanner(f"algorithm: one of {sorted(ALGORITHMS)}, not {self.algorithm!r}")
        ou.setLogLevel(ou.LogLevel.LOG_WARN)  # OMPL's INFO lines would fill the host's log

    def create_plan(self, start: Any, goal: Any, cancel_checker: Callable[[], bool]) -> Any:
        costmap, (sx, sy, _), (gx, gy, gyaw) = self.costmap, pose_xy_yaw(start), pose_xy_yaw(goal)
        touching = costmap.circumscribed_cost()  # costs from here on touch the robot
        spared = costmap.circumscribed_cost(margin=self.clearance)
        near = costmap.circumscribed_radius + self.clearance  # [m] from the start or the goal

        def is_free(x: float, y: float) -> bool:
            cell = costmap.world_to_map(x, y)
            cost = Costmap.NO_INFORMATION if cell is None else costmap.data[cell[1], cell[0]]
            at_an_end = min(math.hypot(x - sx, y - sy), math.hypot(x - gx, y - gy)) < near
            return bool(cost < (touching if at_an_end else spared))

        if not is_free(sx, sy):
            raise StartOccupied(f"start ({sx:.2f}, {sy:.2f}) is too close to an obstacle")
        if not is_free(gx, gy):
            raise GoalOccupied(f"goal ({gx:.2f}, {gy:.2f}) is too close to an obstacle")
        checks, cancelled = itertools.count(), [False]
        stop = ob.timedPlannerTerminationCondition(self.max_time)

        def valid(state: Any) -> bool:
            if next(checks) % CANCEL_EVERY == 0 and cancel_checker():
                cancelled[0] = True
                stop.terminate()  # Nav2 cancelled: OMPL's solve returns
            return is_free(state[0], state[1])

        setup = og.SimpleSetup(plane(costmap))
        setup.setStateValidityChecker(valid)
        info = setup.getSpaceInformation()
        info.setStateValidityCheckingResolution(
            costmap.resolution / setup.getStateSpace().getMaximumExtent()
        )
        setup.setPlanner(ALGORITHMS[self.algorithm](info))
        setup.setStartAndGoalStates(state(setup, sx, sy), state(setup, gx, gy))
        give_up = time.monotonic() + self.timeout
        # rounds of max_time until a path is found: the planner keeps its tree or roadmap
        while not cancelled[0] and time.monotonic() < give_up:
            setup.solve(stop)
            if setup.haveExactSolutionPath():
                break
            stop = ob.timedPlannerTerminationCondition(self.max_time)
        if cancelled[0] or cancel_checker():
            raise PlannerCancelled("cancelled while OMPL searched")
        if not setup.haveExactSolutionPath():
            raise NoValidPathCouldBeFound(f"OMPL {self.algorithm} found none in {self.timeout} s")
        setup.simplifySolution(0.05)
        path = setup.getSolutionPath()
        path.interpolate(int(path.length() / costmap.resolution) + 2)  # a pose per cell
        xy = np.array([(s[0], s[1]) for s in path.getStates()])
        yaw = np.append(np.arctan2(*np.diff(xy, axis=0)[:, ::-1].T), gyaw)
        return np.column_stack([xy, yaw])


def plane(costmap: Any) -> Any:
    """OMPL's 2-D real vector space over the costmap's extent [m]."""
    space = ob.RealVectorStateSpace(2)
    bounds = ob.RealVectorBounds(2)
    extent = ((costmap.origin_x, costmap.size_x), (costmap.origin_y, costmap.size_y))
    for axis, (low, cells) in enumerate(extent):
        bounds.setLow(axis, low)
        bounds.setHigh(axis, low + cells * costmap.resolution - 1e-6)
    space.setBounds(bounds)
    return space


def state(setup: Any, x: float, y: float) -> Any:
    """An OMPL state of ``setup``'s space at (x, y) [m]."""
    s = setup.getStateSpace().allocState()
    s[0], s[1] = x, y
    return s
