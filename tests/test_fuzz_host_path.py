"""The host's request path (decode, dispatch to a reference planner of each plugin type,
encode the reply) under hostile requests, with Hypothesis: it never raises, every reply
decodes and every failure is a typed error, and no request makes the host import a module.

Two kinds of input: hostile bytes (noise, corrupted vectors, wrong shapes, forged counts) and
well-formed requests of the session the planners serve, with any values the schema allows
(NaN poses, empty plans, 0 x 0 costmaps), which reach the planners' methods. The
coverage-guided run of the same path is tests/fuzz_host_path.py (atheris)."""

from __future__ import annotations

import dataclasses
import gc
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st
from nav2_pyif.server.heap import REGROW, settle_heap
from nav2_pyif_protocol.codec import Request, decode_request, encode_request
from nav2_pyif_protocol.constants import OPS_BY_PLUGIN, Op, PluginType

from tests.host_path import CALL_OPS, REFERENCE, REQUEST_SEEDS, HostPath, seed_inputs
from tests.schema_strategies import HOSTILE_BYTES, requests
from tests.test_fuzz_codec import BOUNDED

pytestmark = pytest.mark.unit

KINDS = st.sampled_from(list(REFERENCE))


@pytest.fixture(scope="module")
def host_path() -> HostPath:
    return HostPath()


def test_every_seed_is_served_within_the_contract(host_path: HostPath) -> None:
    """The seeds themselves (every vector to every planner): the baseline of the fuzzers."""
    for seed in seed_inputs():
        host_path.one_input(seed)


@BOUNDED
@given(kind=KINDS, op=st.sampled_from([*CALL_OPS, None]), payload=HOSTILE_BYTES)
def test_hostile_bytes_get_a_typed_error(
    host_path: HostPath, kind: PluginType, op: str | None, payload: bytes
) -> None:
    reply = host_path.feed(kind, payload, op)
    host_path.restore(kind)
    # A hostile payload may happen to be a valid request (a mutated vector); when it is not,
    # the reply says so with a type.
    assert reply.ok or reply.error is not None


@BOUNDED
@given(kind=KINDS, payload=HOSTILE_BYTES)
def test_hostile_bytes_on_the_cancel_key_get_a_typed_reply(
    host_path: HostPath, kind: PluginType, payload: bytes
) -> None:
    host_path.feed_cancel(kind, payload)


@BOUNDED
@given(st.data())
def test_any_valid_request_of_the_session_is_served_or_refused_with_a_type(
    host_path: HostPath, data: st.DataObject
) -> None:
    kind = data.draw(KINDS)
    op = data.draw(st.sampled_from(sorted(OPS_BY_PLUGIN[kind] - {Op.CANCEL_PLAN})))
    drawn: Request = data.draw(requests(op))
    request = dataclasses.replace(drawn, sid=host_path.sid, epoch=1)
    host_path.feed(kind, encode_request(request), op.value)
    host_path.restore(kind)


def test_an_import_during_a_request_breaks_the_contract(host_path: HostPath) -> None:
    """The import check is live: a module first imported during a request is named."""
    sys.modules["nav2_pyif_fuzz_probe"] = sys  # as an import would add it
    try:
        with pytest.raises(AssertionError, match="nav2_pyif_fuzz_probe"):
            imported = len(sys.modules) - 1
            host_path.check_imports(imported)
    finally:
        del sys.modules["nav2_pyif_fuzz_probe"]


def test_a_message_type_from_the_network_imports_no_module(
    host_path: HostPath, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Regression (found by the hostile peer): an input's type ``P/msg/T`` made the host
    import package P, whatever it was (``this/msg/X`` printed the Zen of Python), to look
    for its messages. Now only a message an installed ROS package generated is imported."""
    canary = tmp_path / "nav2_pyif_canary"
    canary.mkdir()
    (canary / "__init__.py").write_text("raise SystemExit('imported by a request')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    request = decode_request(REQUEST_SEEDS["compute_velocity_commands_inputs"][1])
    inputs = [dict(item, type="nav2_pyif_canary/msg/Scan") for item in request.body["inputs"]]
    hostile = dataclasses.replace(request, body=dict(request.body, inputs=inputs))
    reply = host_path.feed(
        PluginType.CONTROLLER, encode_request(hostile), Op.COMPUTE_VELOCITY_COMMANDS.value
    )
    assert reply.error is not None and "nav2_pyif_canary/msg/Scan" in reply.error.message
    assert "nav2_pyif_canary" not in sys.modules


def test_a_configure_flood_keeps_the_frozen_heap_bounded() -> None:
    """Regression (found by the hostile peer, its worker's RSS growing ~1 MiB/min): every
    configure froze, for ever, what the session it replaced left in reference cycles. Here
    each round replaces a "session" of 1000 objects in cycles, as a configure does; the
    frozen objects now stay within heap.REGROW of what is live."""
    session: list[Any] = []
    settle_heap()
    live = gc.get_freeze_count()
    counts = []
    for _ in range(300):
        session = [[] for _ in range(1000)]
        for item in session:
            item.append(item)  # a reference cycle: only the collector frees it
        settle_heap()
        counts.append(gc.get_freeze_count())
    assert len(session) == 1000
    assert max(counts) <= REGROW * (live + 1000) + 2000, (live, max(counts))
