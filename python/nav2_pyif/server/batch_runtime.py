"""A batch of control cycles served in the worker: one ``compute_velocity_commands_batch``
call for every robot whose request is valid, one reply per request, in order.

Each request is admitted, matched to its session and decoded on its own, so a bad request,
an unknown session or a robot's own error (an exception item, a NaN row) fails that robot
only; an exception from the batched call fails the robots in it, each with its typed error.
A planner class without the batched method (a hot swap to one) is served robot by robot.
"""

from __future__ import annotations

import time
from typing import Any

import msgpack

from nav2_pyif.batch import Batch, as_twist_stamped, can_batch, items
from nav2_pyif.server.runtime import PlannerRuntime, Session

#: The worker pipe's op of a batch: its payload a msgpack list of request bytes
BATCH_OP = "compute_velocity_commands_batch"
CYCLE_OP = "compute_velocity_commands"


def handle_batch(runtime: PlannerRuntime, payload: bytes) -> bytes:
    """msgpack list of request bytes -> msgpack list of reply bytes. Never raises."""
    requests: list[bytes] = msgpack.unpackb(payload)
    if not can_batch(runtime.planner_class):
        return msgpack.packb([runtime.handle(request, CYCLE_OP) for request in requests])
    replies: list[bytes | None] = [None] * len(requests)
    ready: list[tuple[int, Any, Session, tuple[Any, ...]]] = []
    for i, request in enumerate(requests):
        opened = runtime.open_cycle(request)
        if isinstance(opened, bytes):
            replies[i] = opened
        else:
            ready.append((i, *opened))
    if ready:
        for i, reply in _served(runtime, ready):
            replies[i] = reply
    return msgpack.packb(replies)


def _served(
    runtime: PlannerRuntime, ready: list[tuple[int, Any, Session, tuple[Any, ...]]]
) -> list[tuple[int, bytes]]:
    planners = [session.planner for _, _, session, _ in ready]
    poses, velocities, checkers = zip(*(arguments for *_, arguments in ready), strict=True)
    start = time.perf_counter_ns()
    try:
        batch = Batch.of(planners, poses, velocities, checkers)  # type: ignore[arg-type]
        method = runtime.planner_class.compute_velocity_commands_batch  # type: ignore[attr-defined]
        results = items(method(batch), len(ready))
    except BaseException as exc:  # the whole call failed: each robot in it gets the error
        elapsed = time.perf_counter_ns() - start
        return [
            (i, runtime.exception_reply(request, exc, elapsed, log=n == 0))
            for n, (i, request, _, _) in enumerate(ready)
        ]
    elapsed = time.perf_counter_ns() - start
    replies = []
    for (i, request, session, (pose, _, _)), item in zip(ready, results, strict=True):
        try:
            result = as_twist_stamped(item, pose, session.context.robot_base_frame)
        except BaseException as exc:  # this robot's own error item
            replies.append((i, runtime.exception_reply(request, exc, elapsed)))
            continue
        replies.append((i, runtime.close_cycle(request, session, pose, result, elapsed)))
    return replies
