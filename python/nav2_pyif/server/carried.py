"""The control cycle in fewer queries (PROTOCOL.md section 15): a goal check, a progress check or
a command may carry, in its request's ``carry``, the encoded requests of the calls that
follow it in Nav2's control cycle, for keys this host serves (which op may carry which is
``schema.CARRIES``). They run after it, in order and only as far as Nav2 would go
(``schema.GOES_ON``: not when the goal is reached, nor without progress, nor after an error);
their encoded replies travel back in the reply's ``carried``.

Each carried request is served exactly as if it had come on its own key (its session, its
worker, its journal), so the plugins that prepared them read the replies as their own.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import msgpack
from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.constants import ErrorType, Op
from nav2_pyif_protocol.schema import CARRIES, GOES_ON

from nav2_pyif.server.runtime import error_reply, peek_seq

#: (key prefix, op, request bytes) -> reply bytes, or None when this host does not serve it
Route = Callable[[str, str, bytes], bytes | None]

#: the ops whose requests may carry others, by their key's last chunk
CARRIERS: frozenset[str] = frozenset(op.value for op in CARRIES)


def _unpack(data: bytes) -> dict[str, Any]:
    try:
        tree = unpack_bounded(data)
    except Exception:
        return {}
    return tree if isinstance(tree, dict) else {}


def _goes_on(op: Op, answer: dict[str, Any]) -> bool:
    """Whether Nav2 makes the next call of the cycle after this reply."""
    if not answer.get("ok") or not isinstance(answer.get("body"), dict):
        return False
    field, wanted = GOES_ON.get(op, ("", True))
    return not field or answer["body"].get(field) is wanted


def _op_of(request: bytes) -> Op | None:
    try:
        return Op(_unpack(request).get("op"))
    except ValueError:
        return None


def carry_on(op: str, payload: bytes, reply: bytes, route: Route, host_id: str) -> bytes:
    """The reply of ``op`` with the carried calls' replies added, as far as Nav2 would go;
    ``reply`` unchanged when nothing was carried, the call failed, or Nav2 would stop."""
    carrier = Op(op)
    carry = (_unpack(payload).get("body") or {}).get("carry")
    answer = _unpack(reply)
    if not isinstance(carry, list) or not carry or not _goes_on(carrier, answer):
        return reply
    carried: list[dict[str, Any]] = []
    for call in carry:
        key, request = call.get("key"), call.get("payload")
        if not isinstance(key, str) or not isinstance(request, bytes):
            break
        carried_op = _op_of(request)
        if carried_op not in CARRIES[carrier]:
            why = f"{op} may not carry {carried_op and carried_op.value}: send it on its own"
            result: bytes | None = error_reply(
                peek_seq(request), host_id, ErrorType.BAD_REQUEST, why
            )
        else:
            result = route(key, carried_op.value, request)
        if result is None:
            result = error_reply(
                peek_seq(request),
                host_id,
                ErrorType.UNAVAILABLE,
                f"host {host_id} does not serve {key}: send {carried_op} there on its own",
            )
        carried.append({"key": key, "payload": result})
        if carried_op is None or not _goes_on(carried_op, _unpack(result)):
            break  # Nav2 stops here: the next call is not made
    answer["body"]["carried"] = carried
    return msgpack.packb(answer, use_bin_type=True)
