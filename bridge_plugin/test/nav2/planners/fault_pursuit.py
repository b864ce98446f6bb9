"""The full-stack launch test's controller: the reference pure pursuit, which misbehaves on
demand for a while, as a planner under test would. ``ros2 param set /controller_server
FollowPath.fault <kind>`` (with ``FollowPath.fault_for`` seconds, default 1) starts the fault,
which then runs its time (setting ``fault`` back to none does not end it):

- ``hang``: the next call sleeps ``hang_s`` (past the host's deadline, so the host answers
  Unavailable and, past its hang grace, kills and restarts the worker);
- ``no_valid_control``: every call raises NoValidControl until the time is up.
"""

from __future__ import annotations

import time
from typing import Any

from nav2_pyif import NoValidControl
from nav2_pyif_planners.pure_pursuit import RegulatedPurePursuit


class FaultPursuit(RegulatedPurePursuit):
    def configure(self) -> None:
        super().configure()
        self.fault = self.params.declare("fault", "none", "none, hang or no_valid_control")
        self.fault_for = self.params.declare("fault_for", 1.0, "[s] how long the fault lasts")
        self.hang_s = self.params.declare("hang_s", 3.0, "[s] a hang's length")
        self.fault_kind = "none"
        self.fault_until = 0.0

    def on_parameters_changed(self, changed: dict[str, Any]) -> None:
        super().on_parameters_changed(changed)
        kind = changed.get("fault", "none")
        if kind != "none":
            # a restarted worker gets the current parameters at configure: no fault then
            self.fault_kind = str(kind)
            self.fault_until = time.monotonic() + float(self.params["fault_for"])

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        if time.monotonic() < self.fault_until:
            if self.fault_kind == "hang":
                self.fault_until = 0.0  # once: the worker is killed or the call overruns
                time.sleep(float(self.params["hang_s"]))
            elif self.fault_kind == "no_valid_control":
                raise NoValidControl("FaultPursuit: no valid control, on purpose")
        return super().compute_velocity_commands(pose, velocity, goal_checker)
