"""The planner host's Zenoh side: per served key, a queryable for calls (answered in order on
one thread per planner, so planners need not be thread-safe), a queryable for out-of-band
cancellation, queryables for hot swap and for ``nav2-pyif hosts``, and a liveliness token
the plugin watches."""

from __future__ import annotations

import contextlib
import logging
import os
import queue
import secrets
import socket
import threading
import time
from collections import deque
from collections.abc import Callable, Collection
from typing import Any

import msgpack
import zenoh
from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.constants import ErrorType, Op
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.batch_runtime import CYCLE_OP
from nav2_pyif.server.carried import CARRIERS, Route, carry_on
from nav2_pyif.server.log_throttle import ThrottledWarning
from nav2_pyif.server.recording.live import OFF, LiveTap
from nav2_pyif.server.reload_policy import ReloadPolicy
from nav2_pyif.server.runtime import error_reply, peek_seq
from nav2_pyif.server.service import PlannerService
from nav2_pyif.server.spec import PlannerSpec

log = logging.getLogger("nav2_pyif.server.host")

#: The ops a call key may name (``P/rpc/<op>``); cancel_plan has its own key. Any other name
#: is refused here: the worker pipe reads op names as commands (its batch op among them).
CALL_OPS: frozenset[str] = frozenset(op.value for op in Op if op is not Op.CANCEL_PLAN)


def new_host_id() -> str:
    """Unique per host process; a valid key chunk."""
    name = "".join(c if c.isalnum() or c in "-_." else "_" for c in socket.gethostname())
    return f"{name}-{os.getpid()}-{secrets.token_hex(3)}"


def _payload(query: Any) -> bytes:
    return query.payload.to_bytes() if query.payload is not None else b""


def _reload_request(payload: bytes) -> dict[str, Any] | str:
    """A reload request's map ({} for none: a fresh import), or what is wrong with it."""
    if not payload:
        return {}
    try:
        request = unpack_bounded(payload)
    except Exception as exc:
        return f"the request is not valid msgpack ({exc or type(exc).__name__})"
    if not isinstance(request, dict):
        return f"the request is a msgpack {type(request).__name__}, not a map"
    wrong = [
        name
        for name in ("planner", "module")
        if request.get(name) is not None and not isinstance(request[name], str)
    ]
    if request.get("delegates") is not None and not isinstance(request["delegates"], dict):
        wrong.append("delegates")
    return f"its {', '.join(wrong)} has the wrong type" if wrong else request


def _answer(query: Any, reply: bytes) -> None:
    try:
        query.reply(query.key_expr, reply)
    finally:
        query.drop()  # sends the final reply marker now, not at garbage collection


class ServedPlanner:
    """One planner answering under one key prefix.

    Three queryables per key (its calls ``P/rpc/*``, ``P/cancel``, ``P/admin/*``), not one per
    query kind and not one on ``P/**``: Zenoh matches each incoming query against every
    queryable of the session, and at 120 keys four queryables each cost the host a fifth of
    its CPU (perf: 22 % of its time in key-expression intersection), but a
    router's access control lets a robot see only declarations on its calls, cancel and hosts
    keys (the deployment guide), and zenoh-pico sends no query to a key it has seen no queryable
    for. One callback serves all three, on Zenoh's own thread, and only sorts the query: a call
    goes to this key's call thread (answered in order, so planners need not be thread-safe); a
    batched control cycle with nothing queued before it goes straight to its batch; a cancel or
    an admin query to this key's side thread, so it is answered while a call runs."""

    def __init__(
        self,
        session: zenoh.Session,
        keys: KeySpace,
        runtime: PlannerService,
        host_id: str,
        started: float | None = None,
        reload_policy: ReloadPolicy | None = None,
        route: Route | None = None,
        live: LiveTap | None = None,
    ) -> None:
        self.keys = keys
        self.live = live  # None: this host refuses live recording (--allow-live-record)
        self.runtime = runtime
        self.route = route  # the host's other keys, for calls carried in a cycle's query
        # a batch group's member takes its cycles without blocking this key's thread
        self._submit_cycle = getattr(runtime, "submit_cycle", None)
        self.host_id = host_id
        self.reload_policy = reload_policy or ReloadPolicy()
        self.started = time.time() if started is None else started  # unix time
        self.queries = 0  # calls that came on this key's own queries (not carried in another)
        # queries dropped unanswered: another replica's, or on no key of this planner's
        # (a wildcard, an unknown admin verb); every other query gets a reply
        self.dropped = 0
        self.refused_ops = 0  # calls on P/rpc/<op> for no op: answered BadRequest
        self._refused_reload = ThrottledWarning(log)  # any peer may ask, as often as it likes
        # (unix time, label) of each planner this key served, a hot swap's too: who served when
        self.history: deque[tuple[float, str]] = deque([(time.time(), runtime.label)], maxlen=32)
        self._rpc = f"{keys.prefix}/rpc/"
        # answered on this key's side thread; a replica's are dropped before (_on_query)
        self._side_ops = {
            keys.cancel: self._on_cancel,
            keys.admin_reload: self._on_reload,
            keys.admin_info: self._on_info,
            keys.admin_record: self._on_record,
        }
        self._calls: queue.SimpleQueue[tuple[Any, str] | None] = queue.SimpleQueue()
        self._side: queue.SimpleQueue[tuple[Any, Callable[[Any], None]] | None]
        self._side = queue.SimpleQueue()
        self._order = threading.Lock()
        self._queued = 0  # calls given to the call thread and not yet answered
        self._threads = [
            threading.Thread(target=self._serve, name=f"planner:{keys.prefix}", daemon=True),
            threading.Thread(target=self._serve_side, name=f"side:{keys.prefix}", daemon=True),
        ]
        for thread in self._threads:
            thread.start()
        self._queryables = [
            session.declare_queryable(key, zenoh.handlers.Callback(self._on_query, indirect=False))
            for key in (keys.calls, keys.cancel, keys.admin)
        ]
        # Announce last: a plugin that sees the token can call at once.
        self._token = session.liveliness().declare_token(keys.host_token(host_id))

    def _on_query(self, query: Any) -> None:
        """On Zenoh's thread: sort the query, answer nothing here (nothing here may block)."""
        key = str(query.key_expr)
        if self._addressed_elsewhere(query):
            self._drop(query)  # a replica's query: its pinned host answers
        elif key.startswith(self._rpc):
            op = key[len(self._rpc) :]
            if op in CALL_OPS:
                with self._order:  # a cycle may not overtake this key's calls still queued
                    self.queries += 1
                    if self._queued == 0 and self._hand_over(query, op):
                        return
                    self._queued += 1
                self._calls.put((query, op))
            elif any(c in op for c in "/*$?#"):
                self._drop(query)  # a wildcard: no key to answer on
            else:
                self._side.put((query, self._on_unknown_op))
        elif (side := self._side_ops.get(key)) is not None:
            self._side.put((query, side))
        else:
            self._drop(query)  # not a query of this key's (a wildcard, another admin verb)

    def _drop(self, query: Any) -> None:
        with self._order:
            self.dropped += 1
        query.drop()

    def _serve(self) -> None:
        while (item := self._calls.get()) is not None:
            query, op = item
            try:
                payload = _payload(query)
                reply = self.runtime.handle(payload, key_op=op)
                if op in CARRIERS and self.route is not None and b"carry" in payload:
                    reply = carry_on(op, payload, reply, self.route, self.host_id)
                query.reply(query.key_expr, reply)
            except Exception:
                log.exception("%s: could not answer a query", self.keys.prefix)
            finally:
                query.drop()  # sends the final reply marker now, not at collection
                with self._order:
                    self._queued -= 1

    def _serve_side(self) -> None:
        while (item := self._side.get()) is not None:
            query, answer = item
            answer(query)

    def _hand_over(self, query: Any, op: str) -> bool:
        """A batched control cycle goes to its batch, whose thread answers the query; not
        one that carries other calls: those run after it, on the call thread."""
        if self._submit_cycle is None or op != CYCLE_OP:
            return False
        payload = _payload(query)
        if b"carry" in payload:
            return False
        self._submit_cycle(payload, lambda reply: _answer(query, reply))
        return True

    def _addressed_elsewhere(self, query: Any) -> bool:
        """Plugins pin one host among replicas with the selector parameter host=<id>."""
        host = query.parameters.get("host")
        return host is not None and host != self.host_id

    def _on_unknown_op(self, query: Any) -> None:
        self.refused_ops += 1
        op = str(query.key_expr)[len(self._rpc) :]
        try:
            payload = _payload(query)
            known = ", ".join(sorted(CALL_OPS))
            message = f"{self.keys.prefix}: no operation {op!r}; known: {known}"
            reply = error_reply(peek_seq(payload), self.host_id, ErrorType.BAD_REQUEST, message)
            query.reply(query.key_expr, reply)
        except Exception:
            log.exception("%s: could not refuse a query", self.keys.prefix)
        finally:
            query.drop()

    def _on_cancel(self, query: Any) -> None:
        try:
            query.reply(query.key_expr, self.runtime.handle_cancel(_payload(query)))
        except Exception:
            log.exception("%s: could not answer a cancel", self.keys.prefix)
        finally:
            query.drop()

    def info(self) -> dict[str, Any]:
        """What ``nav2-pyif hosts`` shows about this key (PROTOCOL.md section 1)."""
        return {
            "host_id": self.host_id,
            "key": self.keys.prefix,
            "planner": self.runtime.label,
            "plugin_type": self.runtime.plugin_type.value,
            "isolation": self.runtime.isolation,
            "sessions": len(self.runtime.journal),
            "history": [list(entry) for entry in self.history],
            "queries": self.queries,
            "dropped": self.dropped,
            "refused_ops": self.refused_ops,
            "started": self.started,
            "pid": os.getpid(),
            "hostname": socket.gethostname(),
        } | ({"batch": batch} if (batch := getattr(self.runtime, "batch", None)) else {})

    def _on_info(self, query: Any) -> None:
        try:
            query.reply(query.key_expr, msgpack.packb(self.info()))
        except Exception:
            log.exception("%s: could not answer an info query", self.keys.prefix)
        finally:
            query.drop()

    def _on_record(self, query: Any) -> None:
        """``nav2-pyif record``: start, renew or stop streaming this key's calls."""
        try:
            request = msgpack.unpackb(_payload(query)) if query.payload is not None else {}
            if self.live is None:
                answer: dict[str, Any] = {"ok": False, "message": f"refused by the host: {OFF}"}
                if isinstance(request, dict) and request.get("action") == "start":
                    log.warning("%s: refused a live recording: %s", self.keys.prefix, OFF)
            else:
                answer = self.live.answer(self.keys.prefix, request, self._restore_requests)
            query.reply(query.key_expr, msgpack.packb(answer))
        except Exception:
            log.exception("%s: could not answer a record request", self.keys.prefix)
        finally:
            query.drop()

    def _restore_requests(self) -> list[bytes]:
        """The requests that rebuild this key's live sessions (configure, the plan, ...)."""
        return [
            payload
            for _sid, (_version, requests) in self.runtime.journal.snapshot().items()
            for _op, payload in requests
        ]

    def _on_reload(self, query: Any) -> None:
        """Hot swap request: {planner?, module?, delegates?} -> {ok, message}. Loading takes
        a while: done on a thread of its own so the key's side thread answers cancels
        meanwhile."""
        threading.Thread(target=self._reload, args=(query,), daemon=True).start()

    def _reload(self, query: Any) -> None:
        try:
            request = _reload_request(_payload(query))
            if isinstance(request, str):  # malformed: refused as the allow-list refuses
                self._refused_reload(f"{self.keys.prefix}: refused a remote reload: {request}")
                answer = {"ok": False, "message": f"reload refused by the host: {request}"}
            else:
                answer = self._reload_as(request)
        except Exception as exc:
            log.exception("%s: reload failed", self.keys.prefix)
            answer = {"ok": False, "message": f"reload failed: {exc}"}
        try:
            query.reply(query.key_expr, msgpack.packb(answer))
        finally:
            query.drop()

    def _reload_as(self, request: dict[str, Any]) -> dict[str, Any]:
        """The answer to a well-formed reload request."""
        current = getattr(self.runtime, "spec", None)
        spec = None
        if isinstance(current, PlannerSpec):
            spec = current.with_planner(
                request.get("planner"), request.get("module"), request.get("delegates")
            )
        requested = spec if spec != current else None  # None: a fresh import
        wanted = requested or current
        what = ("" if requested else "a fresh import of ") + (
            wanted.describe() if isinstance(wanted, PlannerSpec) else "?"
        )
        refusal = self.reload_policy.refusal(requested)
        if refusal:
            self._refused_reload(
                "%s: refused a remote reload (%s): %s", self.keys.prefix, what, refusal
            )
            return {"ok": False, "message": f"reload refused by the host: {refusal}"}
        try:
            message = self.reload(spec, allow_type_change=request.get("allow_type_change") is True)
        except PlannerLoadError as exc:
            # A planner that does not load (a SyntaxError, an import error, another plugin
            # type) is refused as the allow-list refuses: said here too, not only to the caller.
            log.warning("%s: refused a remote reload (%s): %s", self.keys.prefix, what, exc)
            return {"ok": False, "message": str(exc)}
        log.info("%s", message)
        return {"ok": True, "message": message}

    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str:
        """A hot swap (PlannerService.reload), noted in the key's history."""
        message = self.runtime.reload(spec, allow_type_change=allow_type_change)
        self.history.append((self.runtime.swapped_at, self.runtime.label))
        return message

    def close(self) -> None:
        entities: list[Any] = [self._token, *self._queryables]
        for entity in entities:
            with contextlib.suppress(Exception):  # already gone with the session
                entity.undeclare()
        self._calls.put(None)
        self._side.put(None)
        for thread in self._threads:
            thread.join(timeout=5.0)
        self.runtime.close()


class ReachWatch:
    """Says in the log whether this host reaches anything over Zenoh: a warning, repeated
    every ``every`` seconds, while no router, peer or plugin is connected (a host that
    reaches nothing cannot be reached by Nav2), and once what it reached. A host that only
    listens, once its plugins have come and gone, says so once: a plugin that stops (a sim
    run that ends, a robot switched off) is no fault of the host's."""

    def __init__(
        self,
        session: zenoh.Session,
        connect: list[str],
        listen: list[str],
        *,
        grace: float = 3.0,
        every: float = 10.0,
    ) -> None:
        self.session = session
        self.connect, self.listen = connect, listen
        self.every = every
        self.reached = False
        self._lost_at: float | None = None  # when the last connection closed
        self._next_warning = time.monotonic() + grace

    def check(self) -> None:
        transports = list(self.session.info.transports())
        now = time.monotonic()
        if transports:
            if not self.reached:
                self.reached = True
                log.info("Zenoh: reached %s", _describe(transports))
            return
        if self.reached:
            self.reached, self._lost_at = False, now
            self._next_warning = now + self.every
            if self.connect:
                log.warning("Zenoh: every connection is gone; %s", self._advice())
            else:
                log.info("Zenoh: the last connection closed; %s", self._waiting())
        elif now >= self._next_warning and (self.connect or self._lost_at is None):
            self._next_warning = now + self.every
            if self._lost_at is None:
                log.warning("Zenoh: nothing reached yet; %s", self._advice())
            else:
                log.warning(
                    "Zenoh: still nothing reached, %.0f s after the last connection closed; %s",
                    now - self._lost_at,
                    self._advice(),
                )

    def _waiting(self) -> str:
        where = f"listening on {', '.join(self.listen)}" if self.listen else "listening"
        return f"waiting for a Nav2 plugin to connect ({where})"

    def _advice(self) -> str:
        listening = f"listening on {', '.join(self.listen)}" if self.listen else ""
        if not self.connect:
            return (
                f"no Nav2 plugin has connected: {self._waiting()}; point the plugin's Zenoh at it"
            )
        return (
            f"no Zenoh router or peer answers at {', '.join(self.connect)}"
            + (f" and none connected ({listening})" if listening else "")
            + ", so no Nav2 plugin can reach this host. Start a router there (zenohd, or "
            "nav2-pyif router), or let this host listen (--listen ENDPOINT) and point the "
            "plugin at it."
        )


def _describe(transports: list[Any]) -> str:
    named = [f"{t.whatami} {str(t.zid)[:8]}" for t in transports]
    more = f" and {len(named) - 4} more" if len(named) > 4 else ""
    return ", ".join(named[:4]) + more


class PlannerHost:
    """Serves any number of planners (keys) over one Zenoh session."""

    def __init__(
        self,
        session: zenoh.Session,
        host_id: str | None = None,
        reload_policy: ReloadPolicy | None = None,
        live: LiveTap | None = None,
    ) -> None:
        self.session = session
        self.live = live
        self.host_id = host_id or new_host_id()
        self.reload_policy = reload_policy or ReloadPolicy()
        self.started = time.time()
        self.served: dict[str, ServedPlanner] = {}

    def serve(self, key_prefix: str, runtime: PlannerService) -> ServedPlanner:
        keys = KeySpace(key_prefix)
        if key_prefix in self.served:
            raise ValueError(f"key {key_prefix!r} is already served by this host")
        served = ServedPlanner(
            self.session,
            keys,
            runtime,
            self.host_id,
            self.started,
            self.reload_policy,
            route=self._route,
            live=self.live,
        )
        self.served[key_prefix] = served
        log.info(
            "serving %s on %s/** (%s, %s)",
            runtime.label,
            key_prefix,
            runtime.plugin_type.value,
            runtime.where,
        )
        return served

    def _route(self, key_prefix: str, op: str, payload: bytes) -> bytes | None:
        """A call carried in another key's query, served as if it came on its own key."""
        served = self.served.get(key_prefix)
        return None if served is None else served.runtime.handle(payload, key_op=op)

    def reload_all(self, keys: Collection[str] | None = None) -> None:
        """SIGHUP: re-import every planner (fresh worker processes) without dropping a key;
        a planner the keys of a batch group share, once. ``keys``: only the planners of
        these keys (--watch: those whose source files changed)."""
        reloaded: set[int] = set()
        for key, served in self.served.items():
            if keys is not None and key not in keys:
                continue
            owner = id(getattr(served.runtime, "owner", served.runtime))
            if owner in reloaded:
                continue
            reloaded.add(owner)
            try:
                log.info("%s", served.reload())
            except Exception as exc:
                log.error("%s: %s", served.keys.prefix, exc)

    def close(self) -> None:
        for served in self.served.values():
            served.close()
        self.served.clear()
