"""A hostile peer over real Zenoh (nav2_pyif_bench.hostile_bench): a live planner host serving
the reference pure pursuit controller, a fuzzing process sending mutated requests (made from
the shared vectors) back to back to every key and op of it, admin and reload included, and a
well-formed client at 20 Hz beside it. For a bounded time here; ``nav2-pyif-bench hostile
--seconds 300`` runs it for minutes (RELIABILITY.md has its figures).

Asserted: the client misses almost no period (a reply later than 50 ms: at most 1 %, the
machine's own stalls aside; zero is not reached, RELIABILITY.md says why); the host and its
worker import nothing while the peer runs; their memory stays flat (a line fit of RSS over time);
every query the peer sends gets a reply that decodes as its op's, or a typed error, or is
dropped, and the host counted each one it dropped."""

from __future__ import annotations

from typing import Any

import pytest
from nav2_pyif_bench import hostile_bench
from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.codec import decode_reply
from nav2_pyif_protocol.constants import Op

from tests.conftest import wait_until

pytestmark = pytest.mark.integration

SECONDS = 50.0
#: RSS growth per query of the peer's that a fit over a short run may show without a leak,
#: after the bench's warm-up: the heap fragmented by the peer's mix of 1 MB costmaps and small
#: blocks, which glibc keeps (RELIABILITY.md measured ~1.2 MiB/min at ~700 queries/s over
#: 330 s, and a 30 s fit swings to 4 MiB/min). Keeping one Python object of ~100 bytes per
#: query, the smallest leak worth finding, would grow RSS by this much at any rate.
FLAT_BYTES_PER_QUERY = 100


@pytest.fixture(scope="module")
def run() -> dict[str, Any]:
    return hostile_bench.run(SECONDS)


def test_the_peer_ran_at_full_rate_on_every_kind_of_key(run: dict[str, Any]) -> None:
    peer = run["peer"]
    assert run["peer_exit_code"] == 0
    assert peer["sent"] > 50 * SECONDS, hostile_bench.report(run)
    assert {"typed error", "admin answer", "no reply"} <= set(peer["outcomes"])


def test_every_query_got_a_typed_reply_or_was_dropped_and_counted(run: dict[str, Any]) -> None:
    peer = run["peer"]
    assert peer["outcomes"].get("contract broken", 0) == 0, peer["broken"]
    assert peer["outcomes"]["no reply"] == run["host_dropped"], hostile_bench.report(run)
    assert run["host_refused_ops"] > 0  # the calls on P/rpc/<no op>, answered BadRequest


def test_the_client_misses_almost_no_period(run: dict[str, Any]) -> None:
    """A reply later than the period counts as missed, unless the test machine itself
    stalled meanwhile (the bench's StallProbe: this process unscheduled over 25 ms). Not
    zero: one key's calls are served in order, so a valid but costly request of the peer's
    (a configure, a 1000 x 1000 costmap) delays the client's call queued behind it; 330 s
    measured 15 such misses in 6 600 cycles (RELIABILITY.md). At most 1 % here."""
    assert run["cycles"] >= 0.95 * SECONDS / hostile_bench.PERIOD
    unexplained = run["missed"] - run["missed_in_machine_stalls"]
    assert unexplained <= 0.01 * run["cycles"], hostile_bench.report(run)
    assert run["client_errors"] == 0, run["client_error_examples"]


def test_the_host_imports_nothing(run: dict[str, Any]) -> None:
    assert run["imported"] == []


def test_host_and_worker_memory_stay_flat(run: dict[str, Any]) -> None:
    """Flat means growing by less than one small object per query the peer sent: the bound
    follows the peer's rate, which doubled with faster machines and would make any fixed
    KiB/min threshold either blind or flaky."""
    rss = run["rss_kib"]
    assert rss["samples"] >= SECONDS  # two a second
    bound_kib_per_min = FLAT_BYTES_PER_QUERY * run["peer"]["rate_hz"] * 60.0 / 1024.0
    assert rss["host_slope_per_min"] < bound_kib_per_min, hostile_bench.report(run)
    assert rss["worker_slope_per_min"] < bound_kib_per_min, hostile_bench.report(run)


def test_a_call_key_naming_no_op_is_refused_and_the_worker_lives(
    start_host: Any, zsession_factory: Any
) -> None:
    """Regression: nine bytes on ``<key>/rpc/compute_velocity_commands_batch`` crashed the
    planner worker (the worker pipe took the key's last chunk as a command: its batch op),
    and a stream of them kept the key unavailable. Now any op the key does not name is
    answered BadRequest by the host, and counted."""
    key = "nav2_pyif/hostile/FollowPath"
    host = start_host("--key", key, "--planner", "echo_planners:EchoController")
    session = zsession_factory(host.endpoint)

    def info() -> list[Any]:
        answers = session.get(f"{key}/admin/info", timeout=1.0)
        return [unpack_bounded(r.ok.payload.to_bytes()) for r in answers if r.ok is not None]

    assert wait_until(info, 30), host.log()
    for op in ("compute_velocity_commands_batch", "no_such_op"):
        replies = [
            r.ok.payload.to_bytes()
            for r in session.get(f"{key}/rpc/{op}", payload=b"\xc1garbage", timeout=15.0)
            if r.ok is not None
        ]
        assert len(replies) == 1, host.log()
        error = decode_reply(replies[0], Op.ACTIVATE).error
        assert error is not None and error.type == "BadRequest", error
        assert f"no operation {op!r}" in error.message
    assert info()[0]["refused_ops"] == 2
    assert "restarting" not in host.log(), host.log()
