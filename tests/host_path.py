"""The planner host's request path (decode, dispatch to the planner, encode the reply), in
process, for the fuzzers (tests/test_fuzz_host_path.py, tests/fuzz_host_path.py).

One PlannerRuntime per plugin type, each serving a reference planner with a session
configured and activated from the shared vectors (whose requests all name that session), so
that mutated requests reach the planners' methods, not only SessionUnknown. ``feed`` checks
the contract of every reply: it decodes as a reply to the op, and a failure is a typed error;
and that nothing was imported meanwhile (a hostile request must not make the host import).
"""

from __future__ import annotations

import dataclasses
import logging
import sys

from nav2_pyif.server.loader import load_class
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif_protocol.codec import Reply, decode_reply, decode_request, encode_request
from nav2_pyif_protocol.constants import ErrorType, Op, PluginType

from tests.schema_strategies import INDEX, SEEDS

#: the reference planner each plugin type is fuzzed through (planners/)
REFERENCE = {
    PluginType.CONTROLLER: "nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit",
    PluginType.GLOBAL_PLANNER: "nav2_pyif_planners.astar:AStar",
    PluginType.SMOOTHER: "nav2_pyif_planners.simple_smoother:SimpleSmoother",
    PluginType.GOAL_CHECKER: "nav2_pyif_planners.checker_plugins:StoppedGoalChecker",
    PluginType.PROGRESS_CHECKER: "nav2_pyif_planners.checker_plugins:SimpleProgressChecker",
    PluginType.COSTMAP_LAYER: "nav2_pyif_planners.keepout_layer:KeepOutLayer",
    PluginType.BEHAVIOR: "nav2_pyif_planners.free_backup:FreestBackUp",
}
TYPED_ERRORS = frozenset(e.value for e in ErrorType)
#: every request vector (the fuzzers' seeds): (its op, its bytes), by name
REQUEST_SEEDS = {e["name"]: (e["op"], SEEDS[e["name"]]) for e in INDEX if e["kind"] == "request"}
#: the ops a call key may name (cancel_plan has a key of its own)
CALL_OPS = [op.value for op in Op if op is not Op.CANCEL_PLAN]
#: the runtimes' log: each refused request is logged with its traceback, as the host does
LOG = logging.getLogger("nav2_pyif.fuzz")


class ContractBroken(AssertionError):
    """A reply that breaks the host's contract, or an import a request caused."""


def _configure_request(plugin_type: PluginType) -> bytes:
    """The shared vectors' configure for ``plugin_type`` (one of another type's, retyped,
    where the vectors have none)."""
    for e in INDEX:
        if e["kind"] == "request" and e["op"] == "configure":
            request = decode_request(SEEDS[e["name"]])
            if request.body["plugin_type"] == plugin_type.value:
                return SEEDS[e["name"]]
    body = dict(request.body, plugin_type=plugin_type.value)
    return encode_request(dataclasses.replace(request, body=body))


class HostPath:
    def __init__(self) -> None:
        self.runtimes = {
            kind: PlannerRuntime(load_class(spec), "fuzz-host", label=spec, logger=LOG)
            for kind, spec in REFERENCE.items()
        }
        self.configure = {kind: _configure_request(kind) for kind in REFERENCE}
        self.sid = decode_request(next(iter(self.configure.values()))).sid
        for kind in REFERENCE:
            self.restore(kind)
        # Every vector once on every planner: what the host imports on first use of a path
        # (numpy's, rclpy's) is imported now; afterwards nothing may be.
        for seed in seed_inputs():
            self.one_input(seed)
        self.modules = set(sys.modules)

    def restore(self, kind: PluginType) -> None:
        """Configure and activate the session again when a request ended or replaced it."""
        runtime = self.runtimes[kind]
        session = runtime.sessions.get(self.sid)
        if session is not None and session.active:
            return
        runtime.handle(self.configure[kind], "configure")
        activate = decode_request(REQUEST_SEEDS["activate_request"][1])
        runtime.handle(encode_request(dataclasses.replace(activate, sid=self.sid)), "activate")

    def feed(self, kind: PluginType, payload: bytes, key_op: str | None) -> Reply:
        """One request through ``kind``'s planner, as the host's call thread serves it."""
        imported = len(sys.modules)
        reply_bytes = self.runtimes[kind].handle(payload, key_op)
        try:
            reply = decode_reply(reply_bytes, Op(key_op) if key_op else Op.ACTIVATE)
        except Exception as exc:
            raise ContractBroken(f"undecodable reply {reply_bytes[:200]!r}: {exc}") from exc
        if not reply.ok and (reply.error is None or reply.error.type not in TYPED_ERRORS):
            raise ContractBroken(f"untyped error reply: {reply.error}")
        self.check_imports(imported)
        return reply

    def check_imports(self, before: int) -> None:
        """Raise when sys.modules grew since it held ``before`` modules (after warm-up)."""
        if len(sys.modules) != before and hasattr(self, "modules"):
            new = sorted(set(sys.modules) - self.modules)
            raise ContractBroken(f"a request made the host import {new}")

    def feed_cancel(self, kind: PluginType, payload: bytes) -> None:
        reply = decode_reply(self.runtimes[kind].handle_cancel(payload), Op.CANCEL_PLAN)
        if not reply.ok and (reply.error is None or reply.error.type not in TYPED_ERRORS):
            raise ContractBroken(f"untyped error reply to a cancel: {reply.error}")

    def one_input(self, data: bytes) -> None:
        """Bytes from a fuzzer: the first picks the planner and the key's op, the rest is the
        request (the shared vectors are the seeds: a seed is served as the vector's op)."""
        if len(data) < 2:
            return
        kinds = list(REFERENCE)
        kind = kinds[data[0] % len(kinds)]
        choice = data[1] % (len(CALL_OPS) + 2)
        payload = data[2:]
        if choice == len(CALL_OPS):
            self.feed_cancel(kind, payload)
            return
        op = None if choice > len(CALL_OPS) else CALL_OPS[choice]
        self.feed(kind, payload, op)
        self.restore(kind)


def seed_inputs() -> list[bytes]:
    """The fuzzers' seed corpus: every request vector, to every plugin type, on its op's key
    (cancel_plan's on the cancel key)."""
    out = []
    for op, data in REQUEST_SEEDS.values():
        choice = CALL_OPS.index(op) if op in CALL_OPS else len(CALL_OPS)
        out += [bytes([k, choice]) + data for k in range(len(REFERENCE))]
    return out
