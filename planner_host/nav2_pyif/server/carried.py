"""The control cycle in one query (PROTOCOL.md section 15): an ``is_goal_reached`` request may
carry the progress checker's ``check`` and the controller's ``compute_velocity_commands``
requests, encoded, for keys this host serves. They run after the goal check, in Nav2's order
and only as far as Nav2 would go: the check when the goal is not reached, the controller when
the robot is making progress. Their replies travel back, encoded, in the goal check's reply.

Each carried request is served exactly as if it had come on its own key (its session, its
worker, its journal), so the plugins that prepared them read the replies as their own.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import msgpack
from nav2_pyif_protocol.constants import ErrorType, Op

from nav2_pyif.server.runtime import error_reply, peek_seq

#: (key prefix, op, request bytes) -> reply bytes, or None when this host does not serve it
Route = Callable[[str, str, bytes], bytes | None]


def _unpack(data: bytes) -> dict[str, Any]:
    try:
        tree = msgpack.unpackb(data, raw=False)
    except Exception:
        return {}
    return tree if isinstance(tree, dict) else {}


def carry_on(payload: bytes, reply: bytes, route: Route, host_id: str) -> bytes:
    """The goal check's ``reply`` with the carried calls' replies added (when it says "not
    reached"); ``reply`` unchanged when nothing was carried or the goal check failed."""
    body = _unpack(payload).get("body")
    answer = _unpack(reply)
    if not isinstance(body, dict) or not answer.get("ok") or answer["body"].get("reached"):
        return reply
    carried = answer["body"]
    for key_field, op, verdict in (
        ("then_check", Op.CHECK.value, "making_progress"),
        ("then_compute", Op.COMPUTE_VELOCITY_COMMANDS.value, ""),
    ):
        request, key = body.get(key_field), body.get(f"{key_field}_key")
        if not isinstance(request, bytes) or not isinstance(key, str):
            continue
        result = route(key, op, request)
        if result is None:
            result = error_reply(
                peek_seq(request),
                host_id,
                ErrorType.UNAVAILABLE,
                f"host {host_id} does not serve {key}: send {op} there on its own",
            )
        carried[key_field] = result
        outcome = _unpack(result)
        if not outcome.get("ok") or (verdict and not outcome["body"].get(verdict)):
            break  # Nav2 stops here: the controller is not called
    return msgpack.packb(answer, use_bin_type=True)
