"""Encode and decode requests and replies; validate them against ``schema``.

Canonical form (what makes the C++ and Python codecs agree byte for byte): maps written with
their keys in schema order, optional fields left out when absent (never nil), floats always
float64, ints in their shortest msgpack form, strings as str, byte arrays as bin.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import msgpack

from nav2_pyif_protocol.constants import PROTOCOL_VERSION, ErrorType, Op
from nav2_pyif_protocol.schema import (
    BIN,
    BODIES,
    BOOL,
    FLOAT,
    FLOAT6,
    FLOAT7,
    INT,
    PARAMS,
    REPLY_ENVELOPE,
    REQUEST_ENVELOPE,
    STR,
    STR_MAP,
    STRUCTS,
    Field,
)

Body = dict[str, Any]


class ProtocolError(Exception):
    """A message that breaks the protocol. ``error_type`` is BadRequest or VersionMismatch."""

    def __init__(self, error_type: ErrorType, message: str) -> None:
        super().__init__(message)
        self.error_type = error_type


@dataclass(frozen=True)
class ErrorInfo:
    type: str
    message: str
    traceback: str = ""
    python_type: str = ""


@dataclass(frozen=True)
class Request:
    op: Op
    sid: str
    epoch: int
    seq: int
    body: Body = field(default_factory=dict)
    v: int = PROTOCOL_VERSION


@dataclass(frozen=True)
class Reply:
    seq: int
    ok: bool
    host: str
    body: Body | None = None
    error: ErrorInfo | None = None
    compute_ns: int = 0
    v: int = PROTOCOL_VERSION


def _bad(message: str) -> ProtocolError:
    return ProtocolError(ErrorType.BAD_REQUEST, message)


# --- validation: returns the value in canonical form (maps in schema order) ---------------


def _check_scalar_param(name: str, value: Any) -> None:
    if not isinstance(value, (bool, int, float, str)):
        raise _bad(f"parameter {name!r}: {type(value).__name__} is not bool/int/float/str")


def _canon_params(where: str, value: Any) -> dict[str, Any]:
    if not isinstance(value, Mapping):
        raise _bad(f"{where}: expected a map of parameters, got {type(value).__name__}")
    out: dict[str, Any] = {}
    for name, item in value.items():
        if not isinstance(name, str):
            raise _bad(f"{where}: parameter name {name!r} is not a string")
        if isinstance(item, (list, tuple)):
            for element in item:
                _check_scalar_param(name, element)
            kinds = {type(element) for element in item}
            if len(kinds) > 1:
                raise _bad(f"parameter {name!r}: array mixes {sorted(k.__name__ for k in kinds)}")
            out[name] = list(item)
        else:
            _check_scalar_param(name, item)
            out[name] = item
    return out


def _canon_value(where: str, kind: str, value: Any) -> Any:
    if kind == INT:
        if isinstance(value, bool) or not isinstance(value, int):
            raise _bad(f"{where}: expected int, got {type(value).__name__}")
        return value
    if kind == FLOAT:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _bad(f"{where}: expected float, got {type(value).__name__}")
        return float(value)
    if kind == BOOL:
        if not isinstance(value, bool):
            raise _bad(f"{where}: expected bool, got {type(value).__name__}")
        return value
    if kind == STR:
        if not isinstance(value, str):
            raise _bad(f"{where}: expected str, got {type(value).__name__}")
        return value
    if kind == BIN:
        if not isinstance(value, (bytes, bytearray, memoryview)):
            raise _bad(f"{where}: expected bin, got {type(value).__name__}")
        return bytes(value) if not isinstance(value, bytes) else value
    if kind in (FLOAT6, FLOAT7):
        size = 6 if kind == FLOAT6 else 7
        if not isinstance(value, (list, tuple)) or len(value) != size:
            raise _bad(f"{where}: expected an array of {size} floats")
        return [_canon_value(f"{where}[{i}]", FLOAT, x) for i, x in enumerate(value)]
    if kind == PARAMS:
        return _canon_params(where, value)
    if kind == STR_MAP:
        if not isinstance(value, Mapping) or not all(
            isinstance(k, str) and isinstance(v, str) for k, v in value.items()
        ):
            raise _bad(f"{where}: expected a map of str to str")
        return dict(value)
    if kind in STRUCTS:
        return _canon_map(where, STRUCTS[kind], value)
    raise AssertionError(f"schema kind {kind!r} unknown")


def _canon_map(where: str, fields: tuple[Field, ...], value: Any) -> dict[str, Any]:
    if not isinstance(value, Mapping):
        raise _bad(f"{where}: expected a map, got {type(value).__name__}")
    out: dict[str, Any] = {}
    for f in fields:
        if f.name in value and value[f.name] is not None:
            out[f.name] = _canon_value(f"{where}.{f.name}", f.kind, value[f.name])
        elif f.required:
            raise _bad(f"{where}: missing field {f.name!r}")
    return out


def request_body_fields(op: Op) -> tuple[Field, ...]:
    return BODIES[op][0]


def reply_body_fields(op: Op) -> tuple[Field, ...]:
    return BODIES[op][1]


# --- requests -----------------------------------------------------------------------------


def _parse_op(value: Any) -> Op:
    try:
        return Op(value)
    except ValueError:
        raise _bad(f"unknown op {value!r}; known: {', '.join(o.value for o in Op)}") from None


def encode_request(request: Request) -> bytes:
    body = _canon_map(f"{request.op.value} request", request_body_fields(request.op), request.body)
    return msgpack.packb(
        {
            "v": request.v,
            "op": request.op.value,
            "sid": request.sid,
            "epoch": request.epoch,
            "seq": request.seq,
            "body": body,
        },
        use_bin_type=True,
    )


def _unpack(data: bytes, what: str) -> Any:
    try:
        return msgpack.unpackb(data, raw=False, strict_map_key=False)
    except Exception as exc:
        raise _bad(f"{what} is not valid msgpack: {exc}") from exc


def decode_request(data: bytes) -> Request:
    """Decode and validate a request. Raises ProtocolError (BadRequest / VersionMismatch)."""
    raw = _unpack(data, "request")
    if not isinstance(raw, Mapping):
        raise _bad("request is not a msgpack map")
    version = raw.get("v")
    if version != PROTOCOL_VERSION:
        raise ProtocolError(
            ErrorType.VERSION_MISMATCH,
            f"request speaks protocol version {version!r}; this host speaks {PROTOCOL_VERSION}",
        )
    env = _canon_map("request", tuple(f for f in REQUEST_ENVELOPE if f.name != "body"), raw)
    op = _parse_op(env["op"])
    body = _canon_map(f"{op.value} request body", request_body_fields(op), raw.get("body", {}))
    if env["epoch"] < 1 or env["seq"] < 0:
        raise _bad("request epoch must be >= 1 and seq >= 0")
    return Request(op=op, sid=env["sid"], epoch=env["epoch"], seq=env["seq"], body=body)


# --- replies ------------------------------------------------------------------------------


def encode_reply(reply: Reply, op: Op) -> bytes:
    """Encode a reply to ``op`` (the op decides the body schema)."""
    out: dict[str, Any] = {"v": reply.v, "seq": reply.seq, "ok": reply.ok}
    if reply.ok:
        out["body"] = _canon_map(f"{op.value} reply body", reply_body_fields(op), reply.body or {})
    else:
        error = reply.error or ErrorInfo(ErrorType.BAD_REQUEST.value, "error reply without error")
        out["error"] = {
            "type": error.type,
            "message": error.message,
            "traceback": error.traceback,
            "python_type": error.python_type,
        }
    out["host"] = reply.host
    out["compute_ns"] = reply.compute_ns
    return msgpack.packb(out, use_bin_type=True)


def decode_reply(data: bytes, op: Op) -> Reply:
    """Decode and validate a reply to ``op``. Raises ProtocolError on malformed replies."""
    raw = _unpack(data, "reply")
    if not isinstance(raw, Mapping):
        raise _bad("reply is not a msgpack map")
    if raw.get("v") != PROTOCOL_VERSION:
        raise ProtocolError(
            ErrorType.VERSION_MISMATCH,
            f"reply speaks protocol version {raw.get('v')!r}; this client speaks "
            f"{PROTOCOL_VERSION}",
        )
    env = _canon_map("reply", tuple(f for f in REPLY_ENVELOPE if f.name != "body"), raw)
    if "body" in raw:
        env["body"] = raw["body"]
    if env["ok"]:
        body = _canon_map(f"{op.value} reply body", reply_body_fields(op), env.get("body", {}))
        return Reply(env["seq"], True, env["host"], body=body, compute_ns=env["compute_ns"])
    if "error" not in env:
        raise _bad("error reply without an 'error' map")
    error = ErrorInfo(**env["error"])
    return Reply(env["seq"], False, env["host"], error=error, compute_ns=env["compute_ns"])


def all_finite(values: list[float]) -> bool:
    return all(math.isfinite(x) for x in values)
