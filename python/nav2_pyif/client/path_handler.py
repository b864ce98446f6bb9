"""Client of a Python path handler: what nav2_pyif's C++ PyPathHandler does (Lyrical)."""

from __future__ import annotations

from typing import Any

from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif._messages import pose_to_wire
from nav2_pyif.client.plugin_client import Body, PluginClient
from nav2_pyif.plan import Plan


class PathHandlerClient(PluginClient):
    plugin_type = PluginType.PATH_HANDLER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "path_handler")
        kwargs.setdefault("node", "controller_server")
        super().__init__(*args, **kwargs)
        self._plan: dict[str, Any] | None = None  # the latest plan, for a new session

    def set_plan(self, path: Plan | Any) -> None:
        """``path``: a Plan or a nav_msgs/Path, in its own frame."""
        self._plan = (path if isinstance(path, Plan) else Plan.from_msg(path)).to_wire()
        self._call(Op.SET_PLAN, {"path": self._plan})

    def find_plan_segment(self, pose: Any) -> tuple[int, int]:
        """geometry_msgs/PoseStamped (the plan's frame) -> (start, end) into the plan."""
        return segment_of(self._call(Op.FIND_PLAN_SEGMENT, segment_body(pose)))

    def _restored(self, op: Op) -> Body | None:
        if op is Op.SET_PLAN and self._plan is not None:
            return {"path": self._plan}
        return None


def segment_body(pose: Any) -> Body:
    return {"pose": pose_to_wire(pose)}


def segment_of(reply: Body) -> tuple[int, int]:
    return int(reply["start"]), int(reply["end"])
