"""What each session has told its planner, so a new worker can be told the same.

Recorded from requests whose replies were ok: the configure body (with the latest costmap
substituted in), whether the session is active, merged parameter changes, the latest plan and
speed limit. Replayed, in that order, on a restarted or hot-swapped worker under the same
session id and epoch, so the plugin never notices.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Any

from nav2_pyif_protocol.codec import Request, decode_request, encode_request
from nav2_pyif_protocol.constants import Op

STATE_OPS = frozenset(
    {
        Op.CONFIGURE,
        Op.ACTIVATE,
        Op.DEACTIVATE,
        Op.CLEANUP,
        Op.SET_PARAMETERS,
        Op.SET_PLAN,
        Op.SET_SPEED_LIMIT,
    }
)


@dataclass
class SessionRecord:
    sid: str
    epoch: int
    configure: dict[str, Any]
    active: bool = False
    params: dict[str, Any] = field(default_factory=dict)
    plan: dict[str, Any] | None = None
    speed_limit: dict[str, Any] | None = None
    version: int = 0  # bumped on every change: a hot swap replays what changed meanwhile

    def replay(self) -> list[Request]:
        body = self.configure
        if self.params:
            body = dict(body, params={**body["params"], **self.params})
        requests = [Request(Op.CONFIGURE, self.sid, self.epoch, 0, body)]
        if self.active:
            requests.append(Request(Op.ACTIVATE, self.sid, self.epoch, 0, {}))
        if self.plan is not None:
            requests.append(Request(Op.SET_PLAN, self.sid, self.epoch, 0, self.plan))
        if self.speed_limit is not None:
            requests.append(Request(Op.SET_SPEED_LIMIT, self.sid, self.epoch, 0, self.speed_limit))
        return requests


Snapshot = dict[str, tuple[int, list[tuple[str, bytes]]]]


def _encoded(record: SessionRecord) -> list[tuple[str, bytes]]:
    return [(q.op.value, encode_request(q)) for q in record.replay()]


class Journal:
    def __init__(self) -> None:
        self._sessions: dict[str, SessionRecord] = {}
        self._lock = threading.Lock()

    @staticmethod
    def worth_recording(key_op: str, payload: bytes) -> bool:
        """Cheap pre-check (no decoding) for the hot path: state ops, or a costmap update."""
        try:
            op = Op(key_op)
        except ValueError:
            return False
        return op in STATE_OPS or b"costmap" in payload

    def record(self, payload: bytes) -> None:
        """Note a request that the planner accepted (its reply was ok)."""
        try:
            request = decode_request(payload)
        except Exception:
            return
        with self._lock:
            self._apply(request)

    def _apply(self, request: Request) -> None:
        op, body = request.op, request.body
        if op is Op.CONFIGURE:
            self._sessions[request.sid] = SessionRecord(request.sid, request.epoch, dict(body))
            return
        record = self._sessions.get(request.sid)
        if record is None or record.epoch != request.epoch:
            return
        record.version += 1
        if op is Op.CLEANUP:
            del self._sessions[request.sid]
        elif op in (Op.ACTIVATE, Op.DEACTIVATE):
            record.active = op is Op.ACTIVATE
        elif op is Op.SET_PARAMETERS:
            record.params.update(body["params"])
        elif op is Op.SET_PLAN:
            record.plan = body
        elif op is Op.SET_SPEED_LIMIT:
            record.speed_limit = body
        if "costmap" in body:
            record.configure["costmap"] = body["costmap"]

    def snapshot(self) -> Snapshot:
        """sid -> (version, [(op, encoded request)]) to replay."""
        with self._lock:
            return {sid: (r.version, _encoded(r)) for sid, r in self._sessions.items()}

    def changed_since(self, snapshot: Snapshot) -> Snapshot:
        """Sessions created or changed after ``snapshot`` was taken."""
        with self._lock:
            return {
                sid: (r.version, _encoded(r))
                for sid, r in self._sessions.items()
                if sid not in snapshot or snapshot[sid][0] != r.version
            }

    def forget(self, sid: str) -> None:
        with self._lock:
            self._sessions.pop(sid, None)

    def __len__(self) -> int:
        with self._lock:
            return len(self._sessions)
