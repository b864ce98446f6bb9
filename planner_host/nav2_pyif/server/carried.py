"""The control cycle in one query (PROTOCOL.md section 15): an ``is_goal_reached`` request may
carry the progress checker's ``check`` and the controller's ``compute_velocity_commands``
requests, encoded, for keys this host serves. They run after the goal check, in Nav2's order
and only as far as Nav2 would go: the check when the goal is not reached, the controller when
the robot is making progress. Their replies travel back, encoded, in the goal check's reply.
A ``check`` request may carry the command the same way (when the goal check's carried calls
were prepared for a pose TF has since moved on from).

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


_CHECK = ("then_check", Op.CHECK.value, "making_progress")
_COMPUTE = ("then_compute", Op.COMPUTE_VELOCITY_COMMANDS.value, "")
#: op that carries -> (what its own reply must say for Nav2 to go on, the calls it carries)
CARRIERS: dict[str, tuple[Callable[[dict[str, Any]], bool], tuple[tuple[str, str, str], ...]]] = {
    Op.IS_GOAL_REACHED.value: (lambda body: not body.get("reached"), (_CHECK, _COMPUTE)),
    Op.CHECK.value: (lambda body: bool(body.get("making_progress")), (_COMPUTE,)),
}


def carry_on(op: str, payload: bytes, reply: bytes, route: Route, host_id: str) -> bytes:
    """The reply of ``op`` (a goal check or a progress check) with the carried calls' replies
    added, as far as Nav2 would go; ``reply`` unchanged when nothing was carried, the call
    failed, or Nav2 would stop there (goal reached, no progress)."""
    goes_on, chain = CARRIERS[op]
    body = _unpack(payload).get("body")
    answer = _unpack(reply)
    if not isinstance(body, dict) or not answer.get("ok") or not goes_on(answer["body"]):
        return reply
    carried = answer["body"]
    for key_field, carried_op, verdict in chain:
        request, key = body.get(key_field), body.get(f"{key_field}_key")
        if not isinstance(request, bytes) or not isinstance(key, str):
            continue
        result = route(key, carried_op, request)
        if result is None:
            result = error_reply(
                peek_seq(request),
                host_id,
                ErrorType.UNAVAILABLE,
                f"host {host_id} does not serve {key}: send {carried_op} there on its own",
            )
        carried[key_field] = result
        outcome = _unpack(result)
        if not outcome.get("ok") or (verdict and not outcome["body"].get(verdict)):
            break  # Nav2 stops here: the controller is not called
    return msgpack.packb(answer, use_bin_type=True)
