"""Client of a Python behaviour: what nav2_pyif's C++ behaviour plugin does, in Python."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif._messages import pose_to_wire, twist_stamped_from_wire
from nav2_pyif.behavior import Failure, Status, Step
from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.params import ParamValue


class BehaviorClient(PluginClient):
    """TimedBehavior's calls: ``run`` (onRun), ``cycle_update`` (onCycleUpdate) every cycle
    while it answers RUNNING, ``action_completion`` (onActionCompletion). The costmap is
    behavior_server's local costmap; poses are in its frame (``global_frame``)."""

    plugin_type = PluginType.BEHAVIOR

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "backup")
        kwargs.setdefault("node", "behavior_server")
        super().__init__(*args, **kwargs)
        self._running: dict[str, Any] | None = None  # the on_run of the action under way

    def run(
        self, action: str, command: Mapping[str, ParamValue], pose: Any
    ) -> tuple[Status, Failure]:
        """The action's goal (``action``: e.g. nav2_msgs/action/BackUp; ``command``: its
        fields as plain values) at robot ``pose`` (PoseStamped): SUCCEEDED to start cycling."""
        body = {"action": action, "command": dict(command), "pose": pose_to_wire(pose)}
        reply = self._call(Op.ON_RUN, body)
        status = Status(reply["status"])
        self._running = body if status is Status.SUCCEEDED else None
        return status, Failure(reply["failure"])

    def cycle_update(self, pose: Any, elapsed: float) -> Step:
        """One cycle at ``pose``, ``elapsed`` s after run: the Step (cmd_vel a TwistStamped)."""
        body = {"pose": pose_to_wire(pose), "elapsed": float(elapsed)}
        reply = self._call(Op.ON_CYCLE_UPDATE, body)
        cmd = reply.get("cmd_vel")
        return Step(
            Status(reply["status"]),
            twist_stamped_from_wire(cmd) if cmd is not None else None,
            Failure(reply["failure"]),
            dict(reply.get("feedback", {})),
        )

    def action_completion(self, status: str, elapsed: float) -> None:
        """The action ended ('succeeded', 'failed' or 'cancelled') after ``elapsed`` s."""
        self._running = None
        self._call(Op.ON_ACTION_COMPLETION, {"status": status, "elapsed": float(elapsed)})

    def _restored(self, op: Op) -> dict[str, Any] | None:
        # A restarted host goes on with the action under way from its start (the C++ plugin
        # does the same).
        return self._running if op is Op.ON_RUN else None
