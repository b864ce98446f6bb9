"""Nav2's SimpleSmoother as a nav2_pyif Smoother plugin: ``smoothing.smooth_path`` with Nav2's
parameter names and defaults (nav2_smoother/simple_smoother.cpp), served to smoother_server.

    planner-host --key nav2_pyif/robot1/simple_smoother \\
        --planner nav2_pyif_planners.simple_smoother:SimpleSmoother
"""

from __future__ import annotations

import math

from nav2_pyif import FailedToSmoothPath, Plan, Smoother, SmootherTimedOut
from nav2_pyif.params import ParamValue

from nav2_pyif_planners.smoothing import SmootherSettings, SmoothingTimedOut, smooth_path


class SimpleSmoother(Smoother):
    """Pulls each pose towards its neighbours, keeps the ends of each directional segment,
    never moves a pose onto a lethal cell of smoother_server's costmap (when it has one)."""

    def configure(self) -> None:
        p = self.params
        p.declare("tolerance", 1e-10, "stop when a sweep changes the path by less [m]")
        p.declare("max_its", 1000, "sweeps per pass at most")
        p.declare("w_data", 0.2, "pull towards the original path")
        p.declare("w_smooth", 0.3, "pull towards the neighbours")
        p.declare("do_refinement", True, "smooth the smoothed path again")
        p.declare("refinement_num", 2, "refinement passes")
        self.settings = self._settings()

    def on_parameters_changed(self, changed: dict[str, ParamValue]) -> None:
        self.settings = self._settings()

    def _settings(self) -> SmootherSettings:
        p = self.params
        return SmootherSettings(
            tolerance=float(p["tolerance"]),
            max_its=int(p["max_its"]),
            w_data=float(p["w_data"]),
            w_smooth=float(p["w_smooth"]),
            do_refinement=bool(p["do_refinement"]),
            refinement_num=int(p["refinement_num"]),
        )

    def smooth(self, path: Plan, max_time: float) -> Plan:
        if len(path) == 0:
            raise FailedToSmoothPath("the path to smooth is empty")
        costmap = self.costmap
        costs = costmap.costs_at_world if costmap.size_x and costmap.size_y else None
        try:
            poses = smooth_path(path.xy_yaw, self.settings, costs, max_time or math.inf)
        except SmoothingTimedOut as exc:
            raise SmootherTimedOut(f"{exc} ({max_time:g} s)") from None
        return Plan(poses, path.frame_id, path.stamp_ns)
