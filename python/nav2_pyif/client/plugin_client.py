"""Session, epoch, sequence, timeouts, fail-fast and state re-send: shared by both plugin types.

Rules (PROTOCOL.md, "Client behaviour"):
1. No host alive on the prefix (liveliness): fail at once, no query is sent.
2. No reply within the op's timeout, no host alive, or Unavailable: the plugin type's
   host-failure exception (NoValidControl for a controller), which Nav2 recovers from.
3. SessionUnknown: the host restarted (or another replica answered). Bump the epoch, re-send
   configure (with the costmap), activate if active, then the subclass's state (plan, speed
   limit), then retry the call once.
4. The costmap travels only when its version differs from what this session last delivered.
5. Other error replies raise the nav2_core-named exception they name.

Nav2 may configure a plugin before any host runs: ``defer_configure`` marks the session
configured without one, and the first call that needs the host establishes it as rule 3 does.
The shared session transcripts (protocol/vectors/transcripts) hold these rules: this client and
the C++ plugin's replay them byte for byte (tests/test_transcripts.py).
"""

from __future__ import annotations

import logging
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import zenoh
from nav2_pyif_protocol.bridge_params import default_seconds, timeout_default
from nav2_pyif_protocol.codec import (
    ErrorInfo,
    ProtocolError,
    Reply,
    Request,
    decode_reply,
    encode_request,
)
from nav2_pyif_protocol.constants import ERRORS_BY_PLUGIN, ErrorType, Op, PluginType
from nav2_pyif_protocol.keys import KeySpace
from nav2_pyif_protocol.schema import (
    BODIES,
    COSTMAP_SENT,
    OP_TIMEOUT,
    RESTORED,
    CostmapSent,
    Timeout,
)

from nav2_pyif.client.calls import CallRecord
from nav2_pyif.client.transport import Transport, ZenohTransport, selector
from nav2_pyif.costmap import Costmap
from nav2_pyif.exceptions import NAV2_EXCEPTIONS, Nav2Error, generic_error, host_failure_error
from nav2_pyif.params import ParamValue, declares

log = logging.getLogger("nav2_pyif.client")
Body = dict[str, Any]
# Each op's Timeouts field (schema.py OP_TIMEOUT names the classes after them), by op: looked
# up on every call.
_TIMEOUT_FIELD = {op: timeout.value for op, timeout in OP_TIMEOUT.items()}
# Each op's request fields in wire order.
_REQUEST_FIELDS = {op: [f.name for f in fields[0]] for op, fields in BODIES.items()}


@dataclass(frozen=True)
class Timeouts:
    """Seconds to wait for a reply. ``call`` should stay below the controller period. The
    defaults are the Nav2 plugin's (its timeout parameters, bridge_params.py)."""

    call: float = timeout_default(Timeout.CALL)
    lifecycle: float = timeout_default(Timeout.LIFECYCLE)
    configure: float = timeout_default(Timeout.CONFIGURE)
    plan: float = timeout_default(Timeout.PLAN)
    # How long any call waits for a host that has gone (its liveliness token lost) before it
    # fails, as create_plan always does. 0, the plugin's rule: the control cycle fails at once.
    # The offline runner's lockstep mode sets it: a host whose Zenoh lease lapsed while the
    # machine was overloaded is a fact about the machine, not a verdict on the planner.
    host_wait: float = 0.0


def error_from_reply(error: ErrorInfo, plugin_type: PluginType) -> Nav2Error:
    """The exception a plugin raises for an error reply: the named nav2_core class when it
    belongs to this plugin type; for ``Unavailable`` (the host's worker crashed, is restarting
    or overran its deadline) the host-failure one, which Nav2 recovers from; the generic one
    otherwise (the other protocol errors included)."""
    named = {e.value for e in ERRORS_BY_PLUGIN[plugin_type]}
    if error.type in named:
        cls = NAV2_EXCEPTIONS[error.type]
    elif error.type == ErrorType.UNAVAILABLE.value:
        cls = host_failure_error(plugin_type)
    else:
        cls = generic_error(plugin_type)
    message = error.message if error.type in named else f"[{error.type}] {error.message}"
    return cls(
        message,
        remote_traceback=error.traceback,
        python_type=error.python_type,
        host_failed=error.type == ErrorType.UNAVAILABLE.value,
    )


class PluginClient:
    plugin_type: PluginType

    def __init__(
        self,
        session: zenoh.Session | Transport,
        key_prefix: str,
        costmap: Costmap,
        *,
        name: str,
        node: str,
        params: dict[str, ParamValue] | None = None,
        global_frame: str | None = None,
        robot_base_frame: str = "base_link",
        timeouts: Timeouts | None = None,
        record_calls: bool = False,
        nav2_params: dict[str, ParamValue] | None = None,
        sid: str | None = None,
    ) -> None:
        """``session``: a Zenoh session, or any Transport (MockTransport in tests); ``sid``:
        the session id (a random UUID4 by default; transcripts fix it)."""
        self.transport = session if isinstance(session, Transport) else ZenohTransport(session)
        self.keys = KeySpace(key_prefix)
        self.name = name
        self.node = node
        self.params: dict[str, ParamValue] = dict(params or {})
        # configure's nav2_params (controller_frequency, ...); the costmap's inflation joins
        self.nav2_params: dict[str, ParamValue] = dict(nav2_params or {})
        self.global_frame = global_frame or costmap.frame_id
        self.robot_base_frame = robot_base_frame
        self.timeouts = timeouts or Timeouts()
        self.sid = sid or uuid.uuid4().hex
        self.epoch = 0
        self._seq = 0
        self.costmap = costmap
        self._delivered_costmap: int | None = None
        self.configured = False
        self.established = False  # configured on a host (not only deferred)
        self.active = False
        self.last_host: str | None = None
        self.served: str | None = None  # what the host serves, from its configure reply
        self.host: str | None = None  # the pinned host among replicas
        self.resyncs = 0
        self.undeclared: dict[str, str] = {}  # given parameters the planner ignores
        self.debug_outputs: dict[str, str] = {}  # debug outputs the planner declares: name -> type
        self.failovers = 0
        self.records: list[CallRecord] | None = [] if record_calls else None
        self.hosts = self.transport.hosts(self.keys)

    @property
    def session(self) -> zenoh.Session:
        """The Zenoh session this client queries through (a ZenohTransport's)."""
        if not isinstance(self.transport, ZenohTransport):
            raise TypeError(f"{self.keys.prefix}: this client's transport is not Zenoh")
        return self.transport.session

    # --- public lifecycle ---------------------------------------------------------------
    def wait_for_host(self, timeout: float = default_seconds("wait_for_host")) -> bool:
        """Block until a planner host announces itself on this prefix."""
        return self.hosts.wait(timeout)

    def configure(self) -> dict[str, ParamValue]:
        """Start a session; returns the parameters the planner declared (with values)."""
        self.epoch += 1
        self._delivered_costmap = None
        self.established = False
        body = self._call(Op.CONFIGURE, self._configure_body(), allow_resync=False)
        self.configured = self.established = True
        self.served = body.get("planner")
        self.undeclared = body.get("undeclared") or {}
        self.debug_outputs = body.get("debug_outputs") or {}
        declared: dict[str, ParamValue] = body["declared"]
        if self.undeclared:
            log.warning(
                "%s: the planner ignores parameter(s) %s: %s; %s",
                self.name,
                ", ".join(self.undeclared),
                "; ".join(self.undeclared.values()),
                declares(declared),
            )
        for name, value in declared.items():
            self.params.setdefault(name, value)
        return declared

    def defer_configure(self) -> None:
        """Configured without a host yet (Nav2 configures its plugins at bring-up, maybe
        before any host runs): the first call that needs the host establishes the session
        (configure, activate if active, the state); lifecycle calls before only update the
        local state."""
        self.configured, self.established = True, False

    def activate(self) -> None:
        if self.configured and not self.established:
            self.active = True  # sent when the session is established
            if self.hosts.alive:
                try:
                    self._establish()
                except Nav2Error as exc:
                    if not exc.host_failed:
                        raise
                    log.warning("%s: %s", self.keys.prefix, exc)
            return
        self._call(Op.ACTIVATE, {})
        self.active = True

    def deactivate(self) -> None:
        if self.configured and not self.established:
            self.active = False
            return
        self._call(Op.DEACTIVATE, {})
        self.active = False

    def cleanup(self) -> None:
        send = not self.configured or self.established  # not configured: the call says so
        try:
            if send:
                self._call(Op.CLEANUP, {}, allow_resync=False)
        finally:
            self.configured = self.established = False
            self.active = False

    def set_parameters(self, changes: dict[str, ParamValue]) -> dict[str, str]:
        """Send changed parameters; returns the rejected ones (name -> reason). Before the
        session is established they are only kept for configure."""
        if self.configured and not self.established:
            self.params.update(changes)
            return {}
        rejected: dict[str, str] = self._call(Op.SET_PARAMETERS, {"params": changes})["rejected"]
        self.params.update({k: v for k, v in changes.items() if k not in rejected})
        return rejected

    def update_costmap(self, costmap: Costmap) -> None:
        """The costmap changed (give it a new version); sent with the next call that uses it."""
        self.costmap = costmap

    def close(self) -> None:
        self.hosts.close()

    # --- for subclasses -----------------------------------------------------------------
    def _restored(self, op: Op) -> Body | None:
        """The request body that tells a new session on the host ``op``'s part of what the
        planner was told since configure, for each op ``schema.RESTORED`` lists for this
        plugin type (the plan, the speed limit, ...); None: nothing to re-send."""
        return None

    def _configure_body(self) -> Body:
        body: Body = {
            "plugin_type": self.plugin_type.value,
            "name": self.name,
            "node": self.node,
            "params": self.params,
            "global_frame": self.global_frame,
            "robot_base_frame": self.robot_base_frame,
        }
        nav2 = dict(self.nav2_params)
        if self.costmap.inflation is not None:  # as the C++ plugin reads the inflation layer
            nav2.setdefault("inflation_radius", self.costmap.inflation.inflation_radius)
            nav2.setdefault("cost_scaling_factor", self.costmap.inflation.cost_scaling_factor)
        if nav2:
            body["nav2_params"] = nav2
        return body

    def _timeout(self, op: Op) -> float:
        timeout: float = getattr(self.timeouts, _TIMEOUT_FIELD[op])
        return timeout

    # --- replicas: several hosts may serve one key; this plugin talks to exactly one ------
    def _pin_host(self, alive: frozenset[str]) -> None:
        """Keep the pinned host while it is alive; else pin the smallest alive host id."""
        if self.host not in alive:
            if self.host is not None:
                log.warning(
                    "%s: host %s is gone; using %s", self.keys.prefix, self.host, min(alive)
                )
                self.failovers += 1
            self.host = min(alive)

    def _fail_over(self, avoid: str | None = None) -> bool:
        """Pin another alive host when the pinned one vanished (or, with ``avoid``, did not
        answer or is unavailable). True when the pin changed: the call is then retried once
        there, and the new host's SessionUnknown makes this plugin re-send its state."""
        alive = self.hosts.alive
        if avoid is None and self.host in alive:
            return False
        others = sorted(alive - {self.host, avoid})
        if not others:
            return False
        log.warning("%s: failing over from host %s to %s", self.keys.prefix, self.host, others[0])
        self.host = others[0]
        self.failovers += 1
        return True

    def _host_came_back(self, within: float) -> bool:
        """No reply because the pinned host went (it died, or its lease lapsed; its token goes
        a moment after the query ended), and a host is back ``within`` seconds: ``host_wait``,
        or for a plan-class call what is left of its timeout. The call is then retried once."""
        if within <= 0:
            return False
        deadline = time.monotonic() + within
        if not self.hosts.wait_for(lambda alive: self.host not in alive, min(2.0, within)):
            return False  # alive and silent: a hung host is not waited for again
        return self.hosts.wait_for(bool, max(0.0, deadline - time.monotonic()))

    def selector(self, key: str) -> str:
        """``key?host=<pinned id>``: replicas other than the pinned host drop the query."""
        return selector(key, self.host)

    def _next_request(self, op: Op, body: Body) -> Request:
        self._seq += 1
        return Request(op=op, sid=self.sid, epoch=self.epoch, seq=self._seq, body=body)

    # --- calls carried in another plugin's query (PROTOCOL.md section 15) -----------------
    def _with_costmap(self, op: Op, body: Body) -> tuple[Body, bool, int]:
        """The body as sent (the costmap attached, in schema order, as ``schema.COSTMAP_SENT``
        says the op takes it), whether it carries the costmap, and the costmap's version."""
        version = self.costmap.version
        rule = COSTMAP_SENT[op]
        send_costmap = rule is CostmapSent.ALWAYS or (
            rule is CostmapSent.IF_CHANGED and version != self._delivered_costmap
        )
        if send_costmap:
            merged = dict(body, costmap=self.costmap.to_wire())
            body = {name: merged[name] for name in _REQUEST_FIELDS[op] if name in merged}
        return body, send_costmap, version

    def _prepare(self, op: Op, body: Body) -> Carried | None:
        """An encoded request another plugin's query carries to this plugin's host; None
        when this plugin cannot send one now (not configured)."""
        if not self.configured or not self.established:
            return None
        wire, send_costmap, version = self._with_costmap(op, body)
        request = self._next_request(op, wire)
        return Carried(request, encode_request(request), version, send_costmap)

    def _take(
        self,
        carried: Carried | None,
        reply_bytes: bytes | None,
        body: Body,
    ) -> Body | None:
        """The reply body for Nav2's call ``body``, from the reply ``carried`` got, as
        ``_call`` would return it. None, and the call goes on its own, unless the call is
        the prepared one: its request encodes to the same bytes (seq aside) and nothing was
        sent on this session since it was prepared; or the carried call did not run, its
        host does not serve this key or know this session (SessionUnknown: the call on its
        own re-establishes it)."""
        if carried is None or self._seq != carried.request.seq:
            return None
        wire, _, _ = self._with_costmap(carried.request.op, body)
        if encode_request(replace(carried.request, body=wire)) != carried.payload:
            return None
        return self._settle(carried, reply_bytes)

    def _settle(self, carried: Carried, reply_bytes: bytes | None) -> Body | None:
        if reply_bytes is None:
            return None
        op = carried.request.op
        try:
            reply = decode_reply(reply_bytes, op)
        except ProtocolError as exc:
            raise generic_error(self.plugin_type)(
                f"bad carried reply to {op.value}: {exc}"
            ) from exc
        if reply.seq != carried.request.seq:
            raise generic_error(self.plugin_type)(
                f"carried reply to {op.value} has seq {reply.seq}, expected {carried.request.seq}"
            )
        if reply.ok:
            if carried.sent_costmap:
                self._delivered_costmap = carried.costmap_version
            self.last_host = reply.host
            assert reply.body is not None
            return reply.body
        assert reply.error is not None
        if reply.error.type in (ErrorType.SESSION_UNKNOWN.value, ErrorType.UNAVAILABLE.value):
            return None
        raise error_from_reply(reply.error, self.plugin_type)

    def _call(
        self,
        op: Op,
        body: Body,
        *,
        allow_resync: bool = True,
        allow_failover: bool = True,
        while_waiting: Callable[[int], None] | None = None,
        timeout: float | None = None,
    ) -> Body:
        """One call, following the rules above. ``while_waiting(seq)`` runs about every 5 ms
        while the reply is awaited; ``timeout`` [s] instead of the op's class's."""
        if op is not Op.CONFIGURE and not self.configured:
            raise generic_error(self.plugin_type)(
                f"{op.value} before configure on {self.keys.prefix}"
            )
        wait = self._timeout(op) if timeout is None else timeout
        started = time.monotonic()
        alive = self.hosts.alive  # one snapshot per call: fail-fast check and pinning
        if not alive and (OP_TIMEOUT[op] is Timeout.PLAN or self.timeouts.host_wait > 0):
            # create_plan and smooth run in their server's own thread while the robot follows
            # its last path: they wait, up to their timeout, for a host to come back, as for a
            # slow planner, so that a host restart costs no recovery. The others fail at once,
            # unless host_wait says otherwise.
            plan_wait = wait if OP_TIMEOUT[op] is Timeout.PLAN else 0.0
            self.hosts.wait_for(bool, max(plan_wait, self.timeouts.host_wait))
            alive = self.hosts.alive
        if not alive:
            raise host_failure_error(self.plugin_type)(
                f"no planner host is alive on {self.keys.prefix} (start one: planner-host "
                f"--key {self.keys.prefix} ...); {op.value} not sent",
                host_failed=True,
            )
        self._pin_host(alive)
        if op is not Op.CONFIGURE and not self.established:
            self._establish()  # deferred configure, or a re-establishment that failed before
        # in schema order, as the validation skipped for the control cycle would write it;
        # a retry starts again from Nav2's body (the costmap may have been delivered since)
        wire, send_costmap, version = self._with_costmap(op, body)
        request = self._next_request(op, wire)

        def retry(within: float | None = timeout) -> Body:
            # once, on the new replica, whose SessionUnknown re-sends state
            return self._call(
                op,
                body,
                allow_failover=False,
                while_waiting=while_waiting,
                timeout=within,
            )

        try:
            reply = self._exchange(request, while_waiting, wait)
        except Nav2Error:
            # No reply in time (or a bad one): the pinned replica died (its token may not be
            # gone yet) or hangs. Another alive replica gets the call instead.
            if allow_failover and self._fail_over(avoid=self.host):
                return retry()
            # The only host went: wait for it to come back (host_wait), and a plan-class call
            # for what is left of its timeout, as before a call: a host restart mid-plan then
            # costs a slow plan, not a recovery.
            left = wait - (time.monotonic() - started)
            is_plan = OP_TIMEOUT[op] is Timeout.PLAN
            if allow_failover and self._host_came_back(
                max(self.timeouts.host_wait, left if is_plan else 0.0)
            ):
                return retry(
                    max(0.001, wait - (time.monotonic() - started)) if is_plan else timeout
                )
            raise
        if (
            not reply.ok
            and reply.error is not None
            and allow_failover
            and reply.error.type == ErrorType.UNAVAILABLE.value
            and self._fail_over(avoid=reply.host)
        ):
            return retry()
        if reply.ok:
            if send_costmap:
                self._delivered_costmap = version
            assert reply.body is not None
            return reply.body
        assert reply.error is not None
        if reply.error.type == ErrorType.SESSION_UNKNOWN.value and allow_resync:
            self._reestablish(reply.host)
            return self._call(
                op,
                body,
                allow_resync=False,
                allow_failover=allow_failover,
                while_waiting=while_waiting,
                timeout=timeout,
            )
        raise error_from_reply(reply.error, self.plugin_type)

    def _exchange(
        self, request: Request, while_waiting: Callable[[int], None] | None, timeout: float
    ) -> Reply:
        # The control cycle's body is built in schema order by this package: skip re-checking.
        payload = encode_request(request, validate=request.op is not Op.COMPUTE_VELOCITY_COMMANDS)
        poll = None if while_waiting is None else (lambda: while_waiting(request.seq))
        start = time.perf_counter_ns()
        answer = self.transport.query(self.keys.call(request.op), self.host, payload, timeout, poll)
        elapsed = time.perf_counter_ns() - start
        if answer is None:
            self._record(request, elapsed, 0, len(payload), False)
            raise host_failure_error(self.plugin_type)(
                no_reply_message(request.op.value, self.keys.prefix, elapsed / 1e9, timeout),
                host_failed=True,
            )
        try:
            reply = decode_reply(answer, request.op)
        except ProtocolError as exc:
            raise generic_error(self.plugin_type)(
                f"bad reply to {request.op.value}: {exc}"
            ) from exc
        self._record(request, elapsed, reply.compute_ns, len(payload), reply.ok)
        if reply.seq != request.seq:
            raise generic_error(self.plugin_type)(
                f"reply to {request.op.value} has seq {reply.seq}, expected {request.seq}"
            )
        self.last_host = reply.host
        return reply

    def _record(self, request: Request, total: int, compute: int, size: int, ok: bool) -> None:
        if self.records is not None:
            self.records.append(
                CallRecord(
                    request.op.value,
                    total,
                    compute,
                    size,
                    ok,
                    costmap_sent="costmap" in request.body,
                )
            )

    def _reestablish(self, host: str) -> None:
        log.warning(
            "%s: host %s does not know session %s; re-sending state",
            self.keys.prefix,
            host,
            self.sid[:8],
        )
        self.resyncs += 1
        self._establish()

    def _establish(self) -> None:
        """Configure, activate if active, re-send the state. When it fails the session stays
        configured and not established: the next call tries again, instead of refusing every
        call as "before configure"."""
        try:
            self.configure()
        finally:
            self.configured = True
        try:
            if self.active:
                self._call(Op.ACTIVATE, {}, allow_resync=False)
            for op in RESTORED.get(self.plugin_type, ()):
                body = self._restored(op)
                if body is not None:
                    self._call(op, body, allow_resync=False)
        except Nav2Error:
            self.established = False  # the host lacks part of the state: the next call retries
            raise


@dataclass(frozen=True)
class Carried:
    """A request prepared to travel inside another plugin's query."""

    request: Request
    payload: bytes
    costmap_version: int
    sent_costmap: bool


def no_reply_message(op: str, prefix: str, waited: float, timeout: float) -> str:
    """Why a call has no reply [s]: its timeout ran out, or Zenoh ended the query before
    that, as it does when the host it went to is gone (the C++ plugin says the same, with the
    same 5 % spare: a query that ran out may end a little early by Zenoh's clock)."""
    if waited < timeout * 0.95:
        return (
            f"{op} got no reply from {prefix}: the query ended after {waited * 1000:.0f} ms "
            f"of {timeout * 1000:.0f} (its host went away)"
        )
    return f"{op} got no reply from {prefix} within {timeout * 1000:.0f} ms"
