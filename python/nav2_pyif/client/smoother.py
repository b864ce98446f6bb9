"""Client of a Python smoother: what nav2_pyif's C++ smoother plugin does, in Python."""

from __future__ import annotations

from typing import Any

from nav2_pyif_protocol.constants import Op, PluginType
from nav2_pyif_protocol.schema import SMOOTH_GRACE_S

from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.plan import Plan


class SmootherClient(PluginClient):
    plugin_type = PluginType.SMOOTHER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "simple_smoother")
        kwargs.setdefault("node", "smoother_server")
        super().__init__(*args, **kwargs)
        self.was_completed = True

    def smooth(self, path: Plan | Any, max_time: float) -> Plan:
        """``path``: a Plan or nav_msgs/Path; ``max_time`` [s]. The smoothed Plan (same
        frame); ``was_completed`` says whether the smoother finished (nav2_core's return).
        The reply is awaited ``max_time`` and ``SMOOTH_GRACE_S`` more, or the plan timeout
        when that is longer."""
        plan = path if isinstance(path, Plan) else Plan.from_msg(path)
        body = {"path": plan.to_wire(), "max_time": float(max_time)}
        wait = max(self.timeouts.plan, max_time + SMOOTH_GRACE_S)
        reply = self._call(Op.SMOOTH, body, timeout=wait)
        self.was_completed = reply["was_completed"]
        return Plan.from_wire(reply["path"])
