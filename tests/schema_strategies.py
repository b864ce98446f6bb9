"""Hypothesis strategies for every message of the protocol, derived from schema.py's tables
(no message is listed by hand: a field added there is generated here), and for hostile bytes:
the shared vectors mutated, msgpack of arbitrary values, forged container counts."""

from __future__ import annotations

import json
import struct
from pathlib import Path
from typing import Any

import msgpack
from hypothesis import strategies as st
from nav2_pyif_bench.mutations import mutate
from nav2_pyif_protocol.codec import ErrorInfo, Reply, Request
from nav2_pyif_protocol.constants import ErrorType, Op
from nav2_pyif_protocol.schema import (
    BIN,
    BODIES,
    BOOL,
    FLOAT,
    FLOAT6,
    FLOAT7,
    INT,
    PARAMS,
    ROWS,
    STR,
    STR_MAP,
    STRUCTS,
    UINT,
    UINT32,
    Field,
)

VECTORS = Path(__file__).resolve().parents[1] / "protocol" / "vectors"
INDEX: list[dict[str, str]] = json.loads((VECTORS / "index.json").read_text())["vectors"]
#: every shared vector's bytes, by name: the seeds of the mutations
SEEDS: dict[str, bytes] = {
    e["name"]: (VECTORS / f"{e['name']}.msgpack").read_bytes() for e in INDEX
}

INT64 = st.integers(-(2**63), 2**63 - 1)
FLOATS = st.floats(allow_nan=True, allow_infinity=True)  # the codec carries NaN; the host refuses
TEXT = st.text(max_size=12)
#: a costmap's or a layer window's side: small, so the cells they imply stay small
SIDE = st.integers(0, 6)

_PARAM_SCALARS = [st.booleans(), INT64, FLOATS, TEXT]
PARAM_VALUES = st.one_of(*_PARAM_SCALARS, *(st.lists(s, max_size=4) for s in _PARAM_SCALARS))

_SCALARS: dict[str, st.SearchStrategy[Any]] = {
    INT: INT64,
    UINT: st.integers(0, 2**64 - 1),
    UINT32: st.integers(0, 2**32 - 1),
    FLOAT: FLOATS,
    BOOL: st.booleans(),
    STR: TEXT,
    BIN: st.binary(max_size=16),
    FLOAT6: st.lists(FLOATS, min_size=6, max_size=6),
    FLOAT7: st.lists(FLOATS, min_size=7, max_size=7),
    PARAMS: st.dictionaries(TEXT, PARAM_VALUES, max_size=4),
    STR_MAP: st.dictionaries(TEXT, TEXT, max_size=3),
}


def _rows(row_name: str) -> st.SearchStrategy[bytes]:
    """0 to 3 rows of packed little-endian float64."""
    per_row = ROWS[row_name][0]
    rows = st.lists(st.lists(FLOATS, min_size=per_row, max_size=per_row), max_size=3)
    return rows.map(lambda rs: b"".join(struct.pack(f"<{per_row}d", *r) for r in rs))


def _value(f: Field) -> st.SearchStrategy[Any]:
    if f.kind in STRUCTS:
        one: st.SearchStrategy[Any] = fields_map(STRUCTS[f.kind])
    elif f.rows:
        one = _rows(f.rows)
    elif f.minimum is not None:
        one = st.integers(f.minimum, 2**64 - 1 if f.kind == UINT else 2**63 - 1)
    else:
        one = _SCALARS[f.kind]
    return st.lists(one, max_size=3) if f.many else one


@st.composite
def _map(draw: st.DrawFn, fields: tuple[Field, ...]) -> dict[str, Any]:
    """A map of ``fields`` in schema order; optional ones present or not; a byte field with
    ``cells`` as long as the product of its dimension fields (drawn small)."""
    dims = {d for f in fields for d in f.cells}
    out: dict[str, Any] = {}
    for f in fields:
        if not f.required and not draw(st.booleans()):
            continue
        out[f.name] = draw(SIDE if f.name in dims else _value(f))
    for f in fields:
        if f.cells and f.name in out:
            size = 1
            for d in f.cells:
                size *= out[d]
            out[f.name] = draw(st.binary(min_size=size, max_size=size))
    return out


def fields_map(fields: tuple[Field, ...]) -> st.SearchStrategy[dict[str, Any]]:
    return _map(fields)


OPS = st.sampled_from(list(Op))


@st.composite
def requests(draw: st.DrawFn, op: Op | None = None) -> Request:
    """A valid request of ``op`` (any op when None), as a client may send it."""
    op = op or draw(OPS)
    return Request(
        op=op,
        sid=draw(TEXT),
        epoch=draw(st.integers(1, 2**64 - 1)),
        seq=draw(st.integers(0, 2**64 - 1)),
        body=draw(fields_map(BODIES[op][0])),
    )


@st.composite
def replies(draw: st.DrawFn, op: Op) -> Reply:
    """A valid reply to ``op``: its body, or a typed error."""
    seq, host, compute_ns = draw(st.integers(0, 2**64 - 1)), draw(TEXT), draw(INT64)
    if draw(st.booleans()):
        return Reply(seq, True, host, body=draw(fields_map(BODIES[op][1])), compute_ns=compute_ns)
    error_type = draw(st.sampled_from([e.value for e in ErrorType]))
    error = ErrorInfo(error_type, draw(TEXT), draw(TEXT), draw(TEXT))
    return Reply(seq, False, host, error=error, compute_ns=compute_ns)


# --- hostile bytes ------------------------------------------------------------------------


#: a shared vector with a few bytes flipped, inserted, deleted, cut short or made to claim a
#: big length: what a corrupted or hostile peer sends that still looks like the protocol
mutated_vectors = st.builds(
    mutate, st.randoms(use_true_random=False), st.sampled_from([SEEDS[n] for n in sorted(SEEDS)])
)


MSGPACK_VALUES = st.recursive(
    st.none() | st.booleans() | INT64 | FLOATS | TEXT | st.binary(max_size=8),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(TEXT | INT64, inner, max_size=4),
    max_leaves=20,
)


@st.composite
def envelopes_of_anything(draw: st.DrawFn) -> dict[str, Any]:
    """A request envelope that passes the version check, its other fields anything: the
    decoder's validation of every field gets exercised, not only msgpack's parser."""
    envelope: dict[str, Any] = {"v": 2, "op": draw(OPS.map(lambda o: o.value) | TEXT)}
    for name in ("sid", "epoch", "seq"):
        if draw(st.integers(0, 5)):
            envelope[name] = draw(MSGPACK_VALUES)
    body_fields = BODIES[draw(OPS)][0]
    body = draw(fields_map(body_fields))
    for name in list(body):  # some fields of the wrong kind
        if draw(st.integers(0, 3)) == 0:
            body[name] = draw(MSGPACK_VALUES)
    envelope["body"] = body
    return envelope


_COUNT_WIDTHS = {
    b"\xdd": ">I",
    b"\xdf": ">I",
    b"\xdb": ">I",
    b"\xc6": ">I",
    b"\xdc": ">H",
    b"\xde": ">H",
}


@st.composite
def forged_counts(draw: st.DrawFn) -> bytes:
    """Array, map, str and bin headers claiming up to 2^32 - 1 elements or bytes, nested up
    to 1000 deep (a pattern of one to three headers repeated), with little behind them: what
    would make a naive decoder reserve gigabytes. The padding and the counts near its size
    defeat a decoder that only caps each count at the input's size."""
    padding = draw(st.integers(0, 50_000))
    near = st.integers(0, padding + 64) | st.integers(0, 2**32 - 1)
    heads = st.sampled_from([*_COUNT_WIDTHS, b"\x9f"])
    pattern = draw(st.lists(st.tuples(heads, near), min_size=1, max_size=3))
    out = bytearray()
    for head, count in pattern * draw(st.integers(1, 1000)):
        out += head
        width = _COUNT_WIDTHS.get(head)
        if width is not None:
            out += struct.pack(width, min(count, 2**16 - 1) if width == ">H" else count)
    return bytes(out + draw(st.binary(max_size=64)) + b"\x00" * padding)


def _packed(value: Any) -> bytes:
    packed: bytes = msgpack.packb(value, use_bin_type=True)
    return packed


#: What a hostile peer may send: noise, corrupted vectors, well-formed msgpack of the wrong
#: shape, an envelope with wrong fields, forged counts.
HOSTILE_BYTES = st.one_of(
    st.binary(max_size=256),
    mutated_vectors,
    MSGPACK_VALUES.map(_packed),
    envelopes_of_anything().map(_packed),
    forged_counts(),
)
