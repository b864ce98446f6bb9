"""Property tests of the Python codec (Hypothesis): every message of the schema survives a
round trip byte for byte; any bytes at all decode to a message or raise ProtocolError, never
another exception; and decoding never reserves memory far beyond the bytes it was given.

Each test has a fixed example count, derandomized, so the suite's run is bounded and
repeatable (a few seconds each). A longer, random campaign raises the count:

    NAV2_PYIF_FUZZ_EXAMPLES=20000 python -m pytest --timeout 0 tests/test_fuzz_codec.py \
        tests/test_fuzz_host_path.py
"""

from __future__ import annotations

import contextlib
import os
import struct
import tracemalloc

import msgpack
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from nav2_pyif_protocol.bounded import FAST_PATH_LEN, MAX_NESTING, structure_problem
from nav2_pyif_protocol.codec import (
    ProtocolError,
    Reply,
    Request,
    decode_reply,
    decode_request,
    encode_reply,
    encode_request,
)
from nav2_pyif_protocol.constants import Op

from tests.schema_strategies import HOSTILE_BYTES, OPS, SEEDS, forged_counts, replies, requests

pytestmark = pytest.mark.unit

EXAMPLES = int(os.environ.get("NAV2_PYIF_FUZZ_EXAMPLES", "300"))
BOUNDED = settings(
    max_examples=EXAMPLES,
    deadline=None,  # tracemalloc slows each example; the example count bounds the run
    derandomize=EXAMPLES <= 300,  # the suite's run is the same every time; a campaign is not
    database=None,  # nothing written into the checkout
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)

#: Decoding may cost this many bytes of Python objects per byte of input, plus a constant:
#: an empty map is one byte on the wire and a 64-byte dict (and its slot) in Python.
BYTES_PER_INPUT_BYTE = 128
CONSTANT_BYTES = 1 << 20


@BOUNDED
@given(requests())
def test_every_request_round_trips_byte_for_byte(request: Request) -> None:
    data = encode_request(request)
    decoded = decode_request(data)
    assert encode_request(decoded) == data
    assert (decoded.op, decoded.sid, decoded.epoch, decoded.seq) == (
        request.op,
        request.sid,
        request.epoch,
        request.seq,
    )


@BOUNDED
@given(st.data())
def test_every_reply_round_trips_byte_for_byte(data: st.DataObject) -> None:
    op = data.draw(OPS)
    reply: Reply = data.draw(replies(op))
    encoded = encode_reply(reply, op)
    decoded = decode_reply(encoded, op)
    assert encode_reply(decoded, op) == encoded
    assert (decoded.seq, decoded.ok, decoded.host, decoded.error) == (
        reply.seq,
        reply.ok,
        reply.host,
        reply.error,
    )


def test_the_strategies_reach_every_op_and_field() -> None:
    """The round trips above are only as good as what they generate: every op's request and
    reply, with every optional field both present and absent, within the suite's examples."""
    seen_ops: set[Op] = set()

    @settings(BOUNDED, max_examples=1500, derandomize=True)  # a loaded machine: no health check
    @given(requests())
    def collect(request: Request) -> None:
        seen_ops.add(request.op)

    collect()
    assert seen_ops == set(Op)


def decodes_or_refuses(data: bytes) -> None:
    """The one contract for bytes from a peer: a message or ProtocolError."""
    with contextlib.suppress(ProtocolError):
        decode_request(data)
    for op in (Op.CONFIGURE, Op.COMPUTE_VELOCITY_COMMANDS, Op.CREATE_PLAN):
        with contextlib.suppress(ProtocolError):
            decode_reply(data, op)


@BOUNDED
@given(HOSTILE_BYTES)
def test_any_bytes_decode_or_raise_protocol_error(data: bytes) -> None:
    decodes_or_refuses(data)


def peak_of_decoding(data: bytes) -> int:
    """Bytes reserved at the peak of decoding ``data``, the smaller of two measures after a
    first decode: a longer campaign saw 1.9 MB once in a while on inputs of 300 bytes that
    a second measure did not repeat (a cache filled once, or another thread's allocation:
    tracemalloc counts every thread's), which is no allocation of this input's."""
    decodes_or_refuses(data)
    return min(_traced_peak(data), _traced_peak(data))


def _traced_peak(data: bytes) -> int:
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        decodes_or_refuses(data)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def assert_bounded(data: bytes) -> None:
    peak = peak_of_decoding(data)
    limit = BYTES_PER_INPUT_BYTE * len(data) + CONSTANT_BYTES
    assert peak <= limit, f"{len(data)} bytes in, {peak} bytes reserved (limit {limit})"


@BOUNDED
@given(st.one_of(HOSTILE_BYTES, forged_counts()))
def test_decoding_never_reserves_far_beyond_the_input(data: bytes) -> None:
    assert_bounded(data)


def nested_headers(head: bytes, count: int, levels: int, size: int) -> bytes:
    """``levels`` nested container headers each claiming ``count``, padded to ``size``."""
    width = ">I" if head in (b"\xdd", b"\xdf") else ">H"
    data = (head + struct.pack(width, count)) * levels
    return data + b"\x00" * (size - len(data))


@pytest.mark.parametrize(
    "data",
    [
        # The regression: msgpack.unpackb reserved each forged array's list at once, 800x a
        # 100 kB input here (16 GB for 2 MB) before it noticed the data was short.
        nested_headers(b"\xdd", 100_000, 1000, 100_000),
        nested_headers(b"\xdd", 2**32 - 1, 1000, 100_000),
        nested_headers(b"\xdf", 50_000, 1000, 100_000),
        nested_headers(b"\xdc", FAST_PATH_LEN, 1000, 3000),  # the fast path's own worst case
        nested_headers(b"\xdc", 65535, 1000, 3000),
        b"\x9f" * 1000,  # fixarrays: 15 each, no count check needed
        b"\xdb\xff\xff\xff\xff" + b"a" * 100,  # a str claiming 4 GiB
        b"\xc6\xff\xff\xff\xff" + b"a" * 100,  # a bin claiming 4 GiB
    ],
    ids=["array32x1000", "array32-4G", "map32x1000", "array16-fast", "array16", "fixarray",
         "str4G", "bin4G"],
)  # fmt: skip
def test_forged_counts_reserve_nothing_they_claim(data: bytes) -> None:
    assert peak_of_decoding(data) < 2 * CONSTANT_BYTES
    with pytest.raises(ProtocolError, match="not valid msgpack"):
        decode_request(data)


def test_a_long_array_the_fast_path_refuses_still_decodes() -> None:
    """A parameter array longer than the fast path's cap: checked, then decoded."""
    request = Request(Op.SET_PARAMETERS, "s", 1, 7, {"params": {"ids": list(range(1000))}})
    assert decode_request(encode_request(request)).body["params"]["ids"] == list(range(1000))


@pytest.mark.parametrize(
    ("data", "problem"),
    [
        (b"\x92\x01", "ends early"),
        (b"\xdd\x00\x01\x00\x00\x01", "65536 elements declared with 1 bytes left"),
        (b"\x91" * (MAX_NESTING + 1) + b"\x00", f"deeper than {MAX_NESTING}"),
        (b"\x01\x02", "1 extra bytes"),
        (b"\xc1", "byte 0xc1 at offset 0 is no msgpack type"),
        (msgpack.packb({"a": [1, 2.5, b"x", "y", None, True]}), ""),
    ],
)
def test_the_structure_check_names_what_is_wrong(data: bytes, problem: str) -> None:
    found = structure_problem(data)
    assert (problem in found) if problem else found == ""


def test_the_structure_check_accepts_every_vector() -> None:
    """The slow path must not refuse what the protocol sends."""
    assert {name: structure_problem(data) for name, data in SEEDS.items()} == {
        name: "" for name in SEEDS
    }
