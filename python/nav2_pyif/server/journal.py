"""What each session has told its planner, so a new worker can be told the same.

Recorded from requests whose replies were ok: the configure body (with the latest costmap
substituted in), whether the session is active, the parameter changes it accepted, and the
latest request of each op a new session is told again (``schema.RESTORED``: the plan, the speed
limit, a behaviour's action under way). Replayed, in that order, on a restarted or hot-swapped
worker under the same session id and epoch, so the plugin never notices.

A hot swap replays every session on the new planner, then, between two calls, only what changed
meanwhile: a session configured meanwhile whole; in one it already has, the parameters, the
costmap, the activation and the restored requests that changed, and a cleanup for one that
ended. Its planner is configured once per session, as the old one was.
"""

from __future__ import annotations

import itertools
import threading
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager
from dataclasses import dataclass, field
from typing import Any

import msgpack
from nav2_pyif_protocol.codec import Request, decode_request, encode_request
from nav2_pyif_protocol.constants import Op, PluginType
from nav2_pyif_protocol.schema import RESTORED

from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.session_limit import MAX_SESSIONS

#: Every op a plugin re-sends to a new session of its own (schema.RESTORED), in that order: a
#: new worker is told the same, from the latest of each the session sent.
RESTORED_OPS = tuple(dict.fromkeys(op for ops in RESTORED.values() for op in ops))
STATE_OPS = frozenset(
    {
        Op.CONFIGURE,
        Op.ACTIVATE,
        Op.DEACTIVATE,
        Op.CLEANUP,
        Op.SET_PARAMETERS,
        Op.ON_ACTION_COMPLETION,  # ends the on_run under way
        *RESTORED_OPS,
    }
)


# Lyrical's cycle may carry the plan and the goal controller_server transformed (a Path or a
# PoseStamped: a 3-field map after the key), which a new worker must get with set_plan.
_FOLLOWED = (b"\xa4plan\x83", b"\xa4goal\x83")

# Names, for the per-call check: Op(name) costs an enum lookup by value on every call.
_STATE_OP_NAMES = frozenset(op.value for op in STATE_OPS)
_OP_NAMES = frozenset(op.value for op in Op)

# Each configure a session record is made from, numbered: a re-configure is a new session.
_configures = itertools.count(1)


@dataclass
class SessionRecord:
    sid: str
    epoch: int
    configure: dict[str, Any]
    active: bool = False
    params: dict[str, Any] = field(default_factory=dict)
    # The latest body of each of RESTORED_OPS (a behaviour's on_run while its action runs)
    restored: dict[Op, dict[str, Any]] = field(default_factory=dict)
    version: int = 0  # bumped on every change: a hot swap replays what changed meanwhile
    configured: int = field(default_factory=lambda: next(_configures))

    def copy(self) -> SessionRecord:
        """A copy that later changes to this record leave alone (they replace the values of
        these dicts, never change them in place)."""
        return SessionRecord(
            self.sid,
            self.epoch,
            dict(self.configure),
            self.active,
            dict(self.params),
            dict(self.restored),
            self.version,
            self.configured,
        )

    def delta(self, before: SessionRecord) -> list[Request] | None:
        """What a planner told this session as it was ``before`` must be told to catch up
        with it now; None when only the whole replay can (a re-configure, an action ended)."""
        if before.configured != self.configured or (
            Op.ON_RUN in before.restored and Op.ON_RUN not in self.restored
        ):
            return None
        requests = []
        params = {k: v for k, v in self.params.items() if before.params.get(k, _UNSET) != v}
        costmap = self.configure["costmap"]
        if params or costmap is not before.configure["costmap"]:
            # set_parameters carries the costmap here: a host takes a session's costmap from
            # any request that has one, and no other op could deliver it without a call
            # into the planner. Host-internal; plugins never send it so.
            body = {"params": params, "costmap": costmap}
            requests.append(Request(Op.SET_PARAMETERS, self.sid, self.epoch, 0, body))
        if self.active != before.active:
            op = Op.ACTIVATE if self.active else Op.DEACTIVATE
            requests.append(Request(op, self.sid, self.epoch, 0, {}))
        requests += [
            Request(op, self.sid, self.epoch, 0, self.restored[op])
            for op in RESTORED_OPS
            if op in self.restored and self.restored[op] is not before.restored.get(op)
        ]
        return requests

    def replay(self) -> list[Request]:
        body = self.configure
        if self.params:
            body = dict(body, params={**body["params"], **self.params})
        requests = [Request(Op.CONFIGURE, self.sid, self.epoch, 0, body)]
        if self.active:
            requests.append(Request(Op.ACTIVATE, self.sid, self.epoch, 0, {}))
        requests += [
            Request(op, self.sid, self.epoch, 0, self.restored[op])
            for op in RESTORED_OPS
            if op in self.restored
        ]
        return requests


Snapshot = dict[str, tuple[int, list[tuple[str, bytes]]]]
_UNSET = object()


def _followed(plan: dict[str, Any] | None, cycle: dict[str, Any]) -> dict[str, Any] | None:
    """The set_plan body that gives a new worker what a Lyrical cycle carried: its plan, and
    its goal or else the goal the plan had."""
    goal = cycle.get("goal", (plan or {}).get("goal"))
    if "plan" in cycle:
        plan = {"path": cycle["plan"]}
    elif plan is None:
        return None  # a goal without a plan: nothing to hand a new worker yet
    return dict(plan, goal=goal) if goal is not None else plan


def _encoded(record: SessionRecord) -> list[tuple[str, bytes]]:
    return _encode_all(record.replay())


def _encode_all(requests: list[Request]) -> list[tuple[str, bytes]]:
    # The catch-up's set_parameters keeps its costmap (see SessionRecord.delta): not checked
    # against the schema, which would drop it; every body here was checked when it came.
    return [
        (q.op.value, encode_request(q, validate=q.op is not Op.SET_PARAMETERS)) for q in requests
    ]


class Journal:
    def __init__(self) -> None:
        self._sessions: dict[str, SessionRecord] = {}  # the one heard from least recently first
        self.max_sessions = MAX_SESSIONS
        self._lock = threading.Lock()

    @staticmethod
    def worth_recording(key_op: str, payload: bytes) -> bool:
        """Cheap pre-check (no decoding) for the hot path: state ops, or a costmap update, or a
        cycle's new plan or goal."""
        return key_op in _STATE_OP_NAMES or (
            key_op in _OP_NAMES
            and (b"costmap" in payload or any(key in payload for key in _FOLLOWED))
        )

    def note(self, key_op: str, payload: bytes, reply: bytes) -> None:
        """Record a request the planner accepted (its reply was ok), leaving out parameter
        changes it rejected: replayed, those would fail the new planner's configure."""
        if not self.worth_recording(key_op, payload):
            return
        answer = _unpacked(reply)
        if not answer.get("ok"):
            return
        try:
            request = decode_request(payload)
        except Exception:
            return
        reply_body = answer.get("body") or {}
        rejected = reply_body.get("rejected") or {}
        with self._lock:
            self._apply(request, rejected, reply_body.get("status"))

    def _apply(self, request: Request, rejected: dict[str, str], status: Any = None) -> None:
        op, body = request.op, request.body
        if op is Op.CONFIGURE:
            self._sessions.pop(request.sid, None)
            if len(self._sessions) >= self.max_sessions:
                # The planner keeps as many (session_limit), so the journal need not keep more:
                # it forgets the session it heard from least recently (the first: see below).
                del self._sessions[next(iter(self._sessions))]
            self._sessions[request.sid] = SessionRecord(request.sid, request.epoch, dict(body))
            return
        record = self._sessions.get(request.sid)
        if record is None or record.epoch != request.epoch:
            return
        self._sessions[request.sid] = self._sessions.pop(request.sid)  # heard from last
        record.version += 1
        if op is Op.CLEANUP:
            del self._sessions[request.sid]
        elif op in (Op.ACTIVATE, Op.DEACTIVATE):
            record.active = op is Op.ACTIVATE
        elif op is Op.SET_PARAMETERS:
            record.params.update((k, v) for k, v in body["params"].items() if k not in rejected)
        elif op is Op.COMPUTE_VELOCITY_COMMANDS:
            plan = _followed(record.restored.get(Op.SET_PLAN), body)
            if plan is not None:
                record.restored[Op.SET_PLAN] = plan
        elif (op is Op.ON_RUN and status != "succeeded") or op is Op.ON_ACTION_COMPLETION:
            record.restored.pop(Op.ON_RUN, None)  # no action under way
        elif op in RESTORED_OPS:
            record.restored[op] = body
        if "costmap" in body:
            record.configure["costmap"] = body["costmap"]

    def snapshot(self) -> Snapshot:
        """sid -> (version, [(op, encoded request)]) to replay."""
        with self._lock:
            return {sid: (r.version, _encoded(r)) for sid, r in self._sessions.items()}

    def records(self) -> dict[str, SessionRecord]:
        """Every session as it is now, copied."""
        with self._lock:
            return {sid: r.copy() for sid, r in self._sessions.items()}

    def changed_since(self, before: dict[str, SessionRecord]) -> Snapshot:
        """What a planner told the sessions ``before`` (records()) must be told to catch up:
        the whole replay of a session new since, the delta of one changed since, a cleanup of
        one ended since."""
        with self._lock:
            changed: Snapshot = {}
            for sid, record in self._sessions.items():
                old = before.get(sid)
                if old is not None and (old.configured, old.version) == (
                    record.configured,
                    record.version,
                ):
                    continue  # (a re-configure starts again from version 0)
                delta = record.delta(old) if old is not None else None
                requests = record.replay() if delta is None else delta
                changed[sid] = (record.version, _encode_all(requests))
            for sid, old in before.items():
                if sid not in self._sessions:
                    cleanup = Request(Op.CLEANUP, sid, old.epoch, 0, {})
                    changed[sid] = (old.version, _encode_all([cleanup]))
            return changed

    def hand_over(
        self,
        call: Callable[[str, bytes], bytes | None],
        new: tuple[str, PluginType],
        serving: PluginType,
        lock: AbstractContextManager[Any],
        swap: Callable[[], None],
        allow_type_change: bool = False,
    ) -> int:
        """Hot swap, all or nothing: replay every session on the new planner (``new``: its
        label and kind) through ``call``, then, holding ``lock`` so that no call changes them
        meanwhile, what changed since (changed_since: never a second configure of a session
        the new planner has), and ``swap()``. Raises PlannerLoadError naming
        the first session and step that failed (nothing swapped). Returns the number of
        sessions carried over.

        A planner of another kind is refused: the Nav2 YAML names the key for one plugin type
        (a controller's key turned into a global planner's answers nothing its plugin sends).
        With ``allow_type_change`` it is taken, but only with no live session."""
        label, kind = new
        if kind is not serving and (len(self) or not allow_type_change):
            why = (
                f"{len(self)} live session(s) of the {serving.value} would break"
                if len(self)
                else "ask for it explicitly (nav2-pyif reload --allow-type-change)"
            )
            raise PlannerLoadError(
                f"{label} is a {kind.value}; this key serves a {serving.value}: {why}"
            )
        before = self.records()
        _replay_all_or_refuse(
            {sid: (r.version, _encoded(r)) for sid, r in before.items()}, call, label
        )
        with lock:
            _replay_all_or_refuse(self.changed_since(before), call, label)
            swap()
            return len(self)

    def forget(self, sid: str) -> None:
        with self._lock:
            self._sessions.pop(sid, None)

    def __len__(self) -> int:
        with self._lock:
            return len(self._sessions)


def _unpacked(reply: bytes | None) -> dict[str, Any]:
    try:
        answer = msgpack.unpackb(reply) if reply is not None else {}
    except Exception:
        return {}
    return answer if isinstance(answer, dict) else {}


def failure_of(reply: bytes | None) -> str:
    """Why a replayed request failed ("" when its reply was ok)."""
    if reply is None:
        return "no answer within its deadline"
    answer = _unpacked(reply)
    if answer.get("ok"):
        return ""
    error = answer.get("error") or {}
    return f"[{error.get('type', '?')}] {error.get('message', 'undecodable reply')}"


def replay(
    snapshot: Snapshot, call: Callable[[str, bytes], bytes | None]
) -> Iterator[tuple[str, str, str]]:
    """Send each session's requests to a new planner through ``call`` (op, request -> reply,
    None when it did not answer in time). Yields ``(sid, op, reason)`` for each session whose
    replay failed, at its first failing request (the rest of that session is skipped)."""
    for sid, (_, requests) in snapshot.items():
        for op, payload in requests:
            reason = failure_of(call(op, payload))
            if reason:
                yield sid, op, reason
                break


def _replay_all_or_refuse(
    snapshot: Snapshot, call: Callable[[str, bytes], bytes | None], label: str
) -> None:
    """A hot swap is all or nothing: every live session must be restored on the new planner
    ``label``. Raises PlannerLoadError naming the first session and step that failed."""
    for sid, op, reason in replay(snapshot, call):
        raise PlannerLoadError(
            f"{label} could not take over live session {sid[:8]}: its {op} failed: {reason}"
        )
