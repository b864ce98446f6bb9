"""The shared vectors are the contract: the Python codec reproduces every one byte for byte.
(That the files are what the generator writes, their .json forms included, is
tests/test_vectors_generated.py's: the generator is a development tool, and this module is
also the protocol package's colcon test.)"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from nav2_pyif_protocol.codec import (
    ProtocolError,
    decode_reply,
    decode_request,
    encode_reply,
    encode_request,
)
from nav2_pyif_protocol.constants import ErrorType, Op

pytestmark = pytest.mark.unit

VECTORS = Path(__file__).resolve().parents[1] / "protocol" / "vectors"
INDEX = json.loads((VECTORS / "index.json").read_text())["vectors"]


@pytest.mark.parametrize("entry", INDEX, ids=[e["name"] for e in INDEX])
def test_vector_decodes_and_reencodes_byte_for_byte(entry: dict[str, str]) -> None:
    data = (VECTORS / f"{entry['name']}.msgpack").read_bytes()
    op = Op(entry["op"])
    if entry["kind"] == "request":
        if entry["name"] == "activate_newer_version":
            with pytest.raises(ProtocolError) as info:
                decode_request(data)
            assert info.value.error_type is ErrorType.VERSION_MISMATCH
            return
        assert encode_request(decode_request(data)) == data
    else:
        assert encode_reply(decode_reply(data, op), op) == data


def test_vectors_cover_every_operation_both_ways() -> None:
    requests = {e["op"] for e in INDEX if e["kind"] == "request"}
    replies = {e["op"] for e in INDEX if e["kind"] == "reply"}
    assert requests == {op.value for op in Op}
    assert replies == {op.value for op in Op}


def test_vectors_include_the_required_edge_cases() -> None:
    names = {e["name"] for e in INDEX}
    assert {
        "set_plan_empty",
        "configure_planner_1x1",
        "create_plan_costmap_1000",
        "compute_velocity_commands_unicode_frame",
        "compute_velocity_commands_nan_velocity",
    } <= names
    big = decode_request((VECTORS / "create_plan_costmap_1000.msgpack").read_bytes())
    assert len(big.body["costmap"]["data"]) == 1000 * 1000
