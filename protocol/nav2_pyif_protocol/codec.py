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

from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.constants import PROTOCOL_VERSION, ErrorType, Op
from nav2_pyif_protocol.schema import (
    BIN,
    BODIES,
    BODY,
    BOOL,
    FLOAT,
    FLOAT6,
    FLOAT7,
    INT,
    PARAMS,
    REPLY_ENVELOPE,
    REQUEST_ENVELOPE,
    ROWS,
    STR,
    STR_MAP,
    STRUCTS,
    UINT,
    UINT32,
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


# --- validation ---------------------------------------------------------------------------
# The happy path does type checks only: no copies, no strings. Error paths name the field.


class _Invalid(Exception):
    def __init__(self, path: str, message: str) -> None:
        super().__init__(message)
        self.path = path
        self.message = message


def _float(value: Any) -> float:
    kind = type(value)
    if kind is float:
        return value  # type: ignore[no-any-return]
    if kind is int:  # a peer may send a whole number as an int: accept it as float64
        return float(value)
    raise _Invalid("", f"expected float, got {kind.__name__}")


def _floats(size: int) -> Any:
    def check(value: Any) -> list[float]:
        if type(value) is not list or len(value) != size:
            if type(value) is tuple and len(value) == size:
                value = list(value)
            else:
                raise _Invalid("", f"expected an array of {size} floats")
        for i, x in enumerate(value):
            if type(x) is not float:
                try:
                    value[i] = _float(x)
                except _Invalid as exc:
                    raise _Invalid(f"[{i}]", exc.message) from None
        return value  # type: ignore[no-any-return]

    return check


def _exact(expected: type) -> Any:
    def check(value: Any) -> Any:
        if type(value) is not expected:
            if expected is bytes and isinstance(value, (bytearray, memoryview)):
                return bytes(value)
            raise _Invalid("", f"expected {_WIRE_NAMES[expected]}, got {type(value).__name__}")
        return value

    return check


_WIRE_NAMES = {int: "int", bool: "bool", str: "str", bytes: "bin"}


def _unsigned(limit: int, name: str) -> Any:
    def check(value: Any) -> int:
        if type(value) is not int:
            raise _Invalid("", f"expected int, got {type(value).__name__}")
        if value < 0:
            raise _Invalid("", f"expected an int >= 0, got {value}")
        if value > limit:
            raise _Invalid("", f"int {value} is out of the {name} range")
        return value

    return check


def _rows(row_size: int) -> Any:
    check_bytes = _exact(bytes)

    def check(value: Any) -> bytes:
        data: bytes = check_bytes(value)
        if len(data) % (row_size * 8):
            raise _Invalid(
                "",
                f"{len(data)} bytes is not a whole number of rows of {row_size} float64 "
                f"({row_size * 8} bytes)",
            )
        return data

    return check


def _scalar_param(name: str, value: Any) -> None:
    if not isinstance(value, (bool, int, float, str)):
        raise _Invalid(
            f"[{name!r}]", f"parameter {name!r}: {type(value).__name__} is not bool/int/float/str"
        )


def _params(value: Any) -> dict[str, Any]:
    if not isinstance(value, Mapping):
        raise _Invalid("", f"expected a map of parameters, got {type(value).__name__}")
    out: dict[str, Any] = {}
    for name, item in value.items():
        if not isinstance(name, str):
            raise _Invalid("", f"parameter name {name!r} is not a string")
        if isinstance(item, (list, tuple)):
            for element in item:
                _scalar_param(name, element)
            kinds = {type(element) for element in item}
            if len(kinds) > 1:
                names = sorted(k.__name__ for k in kinds)
                raise _Invalid(f"[{name!r}]", f"parameter {name!r}: array mixes {names}")
            out[name] = list(item)
        else:
            _scalar_param(name, item)
            out[name] = item
    return out


def _str_map(value: Any) -> dict[str, str]:
    if not isinstance(value, Mapping) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in value.items()
    ):
        raise _Invalid("", "expected a map of str to str")
    return dict(value)


_CHECKERS: dict[str, Any] = {
    INT: _exact(int),
    UINT: _unsigned(2**64 - 1, "uint64"),
    UINT32: _unsigned(2**32 - 1, "uint32"),
    FLOAT: _float,
    BOOL: _exact(bool),
    STR: _exact(str),
    BIN: _exact(bytes),
    FLOAT6: _floats(6),
    FLOAT7: _floats(7),
    PARAMS: _params,
    STR_MAP: _str_map,
}


def _at_least(check: Any, minimum: int) -> Any:
    """An int field with a ``minimum`` in the schema (a request's epoch)."""

    def check_minimum(value: Any) -> int:
        checked: int = check(value)
        if checked < minimum:
            raise _Invalid("", f"expected an int >= {minimum}, got {checked}")
        return checked

    return check_minimum


@dataclass(frozen=True)
class _Compiled:
    """A field table compiled from the schema: each field's checker (or its structure's
    table), and the byte counts that follow from other fields (a costmap's cells)."""

    #: name, checker (None for a structure), required, structure table, many (an array)
    fields: tuple[tuple[str, Any, bool, _Compiled | None, bool], ...]
    cells: tuple[tuple[str, tuple[str, ...]], ...]


def _compile(fields: tuple[Field, ...]) -> _Compiled:
    out: list[tuple[str, Any, bool, _Compiled | None, bool]] = []
    for f in fields:
        if f.kind in STRUCTS:
            out.append((f.name, None, f.required, _compile(STRUCTS[f.kind]), f.many))
        elif f.rows:
            out.append((f.name, _rows(ROWS[f.rows][0]), f.required, None, f.many))
        elif f.minimum is not None:
            out.append((f.name, _at_least(_CHECKERS[f.kind], f.minimum), f.required, None, f.many))
        else:
            out.append((f.name, _CHECKERS[f.kind], f.required, None, f.many))
    return _Compiled(tuple(out), tuple((f.name, f.cells) for f in fields if f.cells))


def _check_one(struct: _Compiled | None, checker: Any, value: Any, canonical: bool) -> Any:
    return _check_map(struct, value, canonical) if struct else checker(value)


def _check_array(struct: _Compiled | None, checker: Any, value: Any, canonical: bool) -> Any:
    """A field with ``many``: an array, each element checked as the field's kind."""
    if type(value) is not list:
        if type(value) is not tuple:
            raise _Invalid("", f"expected an array, got {type(value).__name__}")
        value = list(value)
    out: list[Any] = [] if canonical else value
    for i, element in enumerate(value):
        try:
            checked = _check_one(struct, checker, element, canonical)
        except _Invalid as exc:
            raise _Invalid(f"[{i}]{exc.path}", exc.message) from None
        if canonical:
            out.append(checked)
        elif checked is not element:
            value[i] = checked
    return out


def _check_cells(compiled: _Compiled, checked: dict[str, Any]) -> None:
    for name, dims in compiled.cells:
        data = checked.get(name)
        sizes = [checked.get(d) for d in dims]
        if data is None or any(size is None for size in sizes):
            continue
        needed = math.prod(sizes)  # type: ignore[arg-type]
        if len(data) != needed:
            raise _Invalid(
                f".{name}",
                f"{len(data)} bytes, but size {' x '.join(map(str, sizes))} needs {needed}",
            )


def _check_map(compiled: _Compiled, value: Any, canonical: bool) -> dict[str, Any]:
    """Check ``value`` against a field table. canonical=False: in place (decoding);
    canonical=True: a new dict in schema order without unknown keys (encoding)."""
    if not isinstance(value, dict):
        raise _Invalid("", f"expected a map, got {type(value).__name__}")
    out = {} if canonical else value
    for name, checker, required, struct, many in compiled.fields:
        item = value.get(name)
        if item is None:
            if required:
                raise _Invalid("", f"missing field {name!r}")
            continue
        try:
            check = _check_array if many else _check_one
            checked = check(struct, checker, item, canonical)
        except _Invalid as exc:
            raise _Invalid(f".{name}{exc.path}", exc.message) from None
        if canonical or checked is not item:
            out[name] = checked
    if compiled.cells:
        _check_cells(compiled, out)
    return out


def _checked(where: str, compiled: _Compiled, value: Any, canonical: bool) -> dict[str, Any]:
    try:
        return _check_map(compiled, value, canonical)
    except _Invalid as exc:
        raise _bad(f"{where}{exc.path}: {exc.message}") from None


_REQUEST_BODIES = {op: _compile(fields[0]) for op, fields in BODIES.items()}
_REPLY_BODIES = {op: _compile(fields[1]) for op, fields in BODIES.items()}
_REQUEST_ENVELOPE = _compile(tuple(f for f in REQUEST_ENVELOPE if f.kind != BODY))
_REPLY_ENVELOPE = _compile(tuple(f for f in REPLY_ENVELOPE if f.kind != BODY))
_ERROR = _compile(STRUCTS["Error"])


# --- requests -----------------------------------------------------------------------------


# A dict, not Op(value): the enum's lookup by value costs ~0.5 µs on every request.
_OPS_BY_VALUE: dict[Any, Op] = {op.value: op for op in Op}


def _parse_op(value: Any) -> Op:
    op = _OPS_BY_VALUE.get(value) if isinstance(value, str) else None
    if op is None:
        raise _bad(f"unknown op {value!r}; known: {', '.join(o.value for o in Op)}")
    return op


def encode_request(request: Request, *, validate: bool = True) -> bytes:
    """Encode a request. ``validate=False`` is for bodies built in schema order by this
    package's own helpers (the control loop's hot path); the bytes are the same."""
    body = request.body
    if validate:
        body = _checked(f"{request.op.value} request", _REQUEST_BODIES[request.op], body, True)
    return _pack(
        {
            "v": request.v,
            "op": request.op.value,
            "sid": request.sid,
            "epoch": request.epoch,
            "seq": request.seq,
            "body": body,
        }
    )


def _pack(message: dict[str, Any]) -> bytes:
    return msgpack.packb(message, use_bin_type=True)  # type: ignore[no-any-return]


def _unpack(data: bytes, what: str) -> Any:
    try:
        return unpack_bounded(data)
    except Exception as exc:  # msgpack's own errors, MemoryError, an unhashable map key...
        # msgpack's FormatError says nothing: its name then
        raise _bad(f"{what} is not valid msgpack: {exc or type(exc).__name__}") from exc


def decode_request(data: bytes) -> Request:
    """Decode and validate a request. Raises ProtocolError (BadRequest / VersionMismatch)."""
    raw = _unpack(data, "request")
    if not isinstance(raw, dict):
        raise _bad("request is not a msgpack map")
    version = raw.get("v")
    if type(version) is not int or version != PROTOCOL_VERSION:  # true / 1.0 are not 1
        raise ProtocolError(
            ErrorType.VERSION_MISMATCH,
            f"request speaks protocol version {version!r}; this host speaks {PROTOCOL_VERSION}",
        )
    _checked("request", _REQUEST_ENVELOPE, raw, False)
    op = _parse_op(raw["op"])
    body = _checked(f"{op.value} request body", _REQUEST_BODIES[op], raw.get("body", {}), False)
    return Request(op=op, sid=raw["sid"], epoch=raw["epoch"], seq=raw["seq"], body=body)


# --- replies ------------------------------------------------------------------------------


def encode_reply(reply: Reply, op: Op, *, validate: bool = True) -> bytes:
    """Encode a reply to ``op`` (the op decides the body schema)."""
    out: dict[str, Any] = {"v": reply.v, "seq": reply.seq, "ok": reply.ok}
    if reply.ok:
        body = reply.body or {}
        out["body"] = (
            _checked(f"{op.value} reply body", _REPLY_BODIES[op], body, True) if validate else body
        )
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
    return _pack(out)


def decode_reply(data: bytes, op: Op) -> Reply:
    """Decode and validate a reply to ``op``. Raises ProtocolError on malformed replies."""
    raw = _unpack(data, "reply")
    if not isinstance(raw, dict):
        raise _bad("reply is not a msgpack map")
    if type(raw.get("v")) is not int or raw.get("v") != PROTOCOL_VERSION:
        raise ProtocolError(
            ErrorType.VERSION_MISMATCH,
            f"reply speaks protocol version {raw.get('v')!r}; this client speaks "
            f"{PROTOCOL_VERSION}",
        )
    _checked("reply", _REPLY_ENVELOPE, raw, False)
    if raw["ok"]:
        body = _checked(f"{op.value} reply body", _REPLY_BODIES[op], raw.get("body", {}), False)
        return Reply(raw["seq"], True, raw["host"], body=body, compute_ns=raw["compute_ns"])
    error = raw.get("error")
    if error is None:
        raise _bad("error reply without an 'error' map")
    _checked("reply.error", _ERROR, error, False)
    return Reply(
        raw["seq"],
        False,
        raw["host"],
        error=ErrorInfo(error["type"], error["message"], error["traceback"], error["python_type"]),
        compute_ns=raw["compute_ns"],
    )


def all_finite(values: list[float]) -> bool:
    return all(math.isfinite(x) for x in values)
