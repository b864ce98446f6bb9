"""Client of a Python global planner, with cancellation while a plan is being computed."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from nav2_pyif_protocol.codec import encode_request
from nav2_pyif_protocol.constants import Op, PluginType

from nav2_pyif._messages import pose_to_wire
from nav2_pyif.client.plugin_client import PluginClient
from nav2_pyif.plan import Plan


class GlobalPlannerClient(PluginClient):
    plugin_type = PluginType.GLOBAL_PLANNER

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("name", "GridBased")
        kwargs.setdefault("node", "planner_server")
        super().__init__(*args, **kwargs)

    def create_plan(
        self,
        start: Any,
        goal: Any,
        cancel_checker: Callable[[], bool] | None = None,
        viapoints: Sequence[Any] = (),
    ) -> Plan:
        """PoseStamped start, goal -> Plan. While waiting, polls ``cancel_checker`` (as Nav2's
        planner_server passes one) and forwards a cancellation to the host once.
        ``viapoints``: PoseStamped poses to pass through (Lyrical), in the start's frame."""
        body: dict[str, Any] = {"start": pose_to_wire(start), "goal": pose_to_wire(goal)}
        if viapoints:
            frame = body["start"]["frame_id"]
            rows = [pose_to_wire(p)["pose"] for p in viapoints]
            body["viapoints"] = Plan(rows, frame, body["goal"]["stamp_ns"]).to_wire()
        while_waiting = None
        if cancel_checker is not None:
            cancel_sent = False

            def while_waiting(seq: int) -> None:
                nonlocal cancel_sent
                if not cancel_sent and cancel_checker():
                    self._send_cancel(seq)
                    cancel_sent = True

        reply = self._call(Op.CREATE_PLAN, body, while_waiting=while_waiting)
        return Plan.from_wire(reply["path"])

    def _send_cancel(self, target_seq: int) -> None:
        cancel = self._next_request(Op.CANCEL_PLAN, {"target_seq": target_seq})
        # Fire and forget: the planner's own reply (PlannerCancelled) is what counts.
        self.transport.send(
            self.keys.cancel, self.host, encode_request(cancel), self._timeout(Op.CANCEL_PLAN)
        )
