"""Feed a recording's calls, in order, to planners served as the host serves them (a
supervised worker, or in process), as fast as they answer, and compare every reply."""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from nav2_pyif.replay.compare import CallDiff, compare
from nav2_pyif.server.recording.format import Recording
from nav2_pyif.server.service import InProcessPlanner, PlannerService
from nav2_pyif.server.spec import PlannerSpec
from nav2_pyif.server.supervisor import Deadlines, SupervisedPlanner

log = logging.getLogger("nav2_pyif.replay")
HOST_ID = "replay"  # the host id the replayed planners see (their sessions are the recorded)


@dataclass
class ReplayResult:
    files: list[Path]
    planners: dict[str, str]  # key -> the planner replayed on it
    recorded: dict[str, str]  # key -> the planner recorded on it
    calls: list[CallDiff] = field(default_factory=list)
    restored: int = 0  # restore requests given before a rotated file's calls
    # hot swaps during the recording: (seconds since its first call, key, the new planner)
    reloads: list[tuple[float, str, str]] = field(default_factory=list)
    wall_s: float = 0.0


def recorded_spec(recording: Recording, key: str) -> PlannerSpec | None:
    """The planner the recording says the key served, to replay it unchanged."""
    planner = recording.keys[key].planner
    if not planner.get("planner") and not planner.get("module"):
        return None
    return PlannerSpec(
        key,
        planner.get("planner"),
        planner.get("module"),
        dict(planner.get("delegates") or {}),
        planner.get("kind"),
    )


def start(spec: PlannerSpec, isolation: str, deadline: float, log_level: str) -> PlannerService:
    """Served as planner-host serves it; deadlines that only a hung planner reaches: a
    replay's verdict must not depend on the machine's load."""
    if isolation == "none":
        return InProcessPlanner(spec, HOST_ID)
    deadlines = Deadlines(call=deadline, configure=deadline, plan=deadline, lifecycle=deadline)
    return SupervisedPlanner(spec, HOST_ID, deadlines=deadlines, log_level=log_level).start()


def replay(
    recording: Recording,
    services: dict[str, PlannerService],
    files: list[Path],
    on_call: Callable[[int, int], None] | None = None,
) -> ReplayResult:
    """Each call of the keys in ``services``, in the recorded order, to its service. Raises
    PlannerLoadError when a planner does not load again at a recorded hot swap."""
    result = ReplayResult(
        files,
        {key: service.label for key, service in services.items()},
        {key: _label(recording, key) for key in services},
    )
    calls = [c for c in recording.calls if c.key in services]
    first = next((c.received_ns for c in calls if not c.restore), 0)
    result.reloads = [
        ((when - first) / 1e9, key, label)
        for when, key, label in recording.reloads
        if key in services
    ]
    # a recorded hot swap is one here too: a fresh import of the replayed planner, its sessions
    # carried over, so what a swap resets (the planner's own state) is reset alike
    swaps = sorted((when, key) for when, key, _ in recording.reloads if key in services)
    started = time.perf_counter()
    for n, call in enumerate(calls):
        while swaps and not call.restore and swaps[0][0] <= call.received_ns:
            services[swaps.pop(0)[1]].reload()
        reply = services[call.key].handle(call.request, key_op=call.op)
        if call.restore:
            result.restored += 1
        else:
            t = (call.received_ns - first) / 1e9
            result.calls.append(compare(len(result.calls), call.key, call.op, t, call.reply, reply))
        if on_call is not None:
            on_call(n + 1, len(calls))
    result.wall_s = time.perf_counter() - started
    return result


def _label(recording: Recording, key: str) -> str:
    spec = recorded_spec(recording, key)
    return spec.describe() if spec is not None else "?"
