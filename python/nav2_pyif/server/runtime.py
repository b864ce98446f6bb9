"""One served planner: sessions, decoding, dispatch to the planner's methods, typed errors.

``PlannerRuntime.handle`` turns request bytes into reply bytes and never raises: whatever the
planner does (raise, return junk, call sys.exit) becomes a typed error reply, logged once
with its traceback. It knows nothing of Zenoh, so it runs in the host process or a worker.
"""

from __future__ import annotations

import logging
import threading
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np
from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.codec import (
    ErrorInfo,
    ProtocolError,
    Reply,
    Request,
    decode_request,
    encode_reply,
)
from nav2_pyif_protocol.constants import INVALID_ERROR, OPS_BY_PLUGIN, ErrorType, Op, PluginType

from nav2_pyif._context import PluginContext
from nav2_pyif._messages import pose_from_wire, stamp_to_ns, twist_from_list
from nav2_pyif._ros_types import warm_serialization
from nav2_pyif.behavior import Behavior, Command, Status
from nav2_pyif.controller import Controller
from nav2_pyif.costmap import Costmap, Inflation
from nav2_pyif.costmap_layer import CostmapLayer, LayerWindow
from nav2_pyif.debug import check_declared
from nav2_pyif.exceptions import (
    NAV2_EXCEPTIONS,
    InvalidPath,
    Nav2Error,
    generic_error,
)
from nav2_pyif.global_planner import GlobalPlanner
from nav2_pyif.goal_checker import GoalChecker
from nav2_pyif.goal_tolerances import GoalTolerances
from nav2_pyif.params import Parameters, declares
from nav2_pyif.path_handler import PathHandler
from nav2_pyif.plan import Plan
from nav2_pyif.plugin import PlannerPlugin
from nav2_pyif.progress_checker import ProgressChecker
from nav2_pyif.server.followed_plan import follow_plan
from nav2_pyif.server.heap import settle_heap
from nav2_pyif.server.log_throttle import ThrottledWarning
from nav2_pyif.server.results import (
    checked_bool,
    checked_bounds,
    checked_layer_costs,
    checked_plan,
    checked_segment,
    checked_smoothed,
    checked_step,
    checked_twist_stamped,
    tolerances_to_wire,
)
from nav2_pyif.server.returns import return_site
from nav2_pyif.server.session_limit import MAX_SESSIONS, session_to_end
from nav2_pyif.smoother import Smoother

MAX_TRACEBACK_CHARS = 16_000
Body = dict[str, Any]


@dataclass
class Session:
    sid: str
    epoch: int
    planner: PlannerPlugin
    context: PluginContext
    active: bool = False
    running_seq: int | None = None
    cancel_requested: threading.Event = field(default_factory=threading.Event)
    last_call: float = field(default_factory=time.monotonic)  # which session_limit ends first


def _qualname(exc: BaseException) -> str:
    return f"{type(exc).__module__}.{type(exc).__qualname__}"


_INTERNAL_DIR = str(Path(__file__).resolve().parent)
_RESULTS_FILE = str(Path(__file__).resolve().parent / "results.py")


def _user_frames(tb: TracebackType | None) -> TracebackType | None:
    """The traceback from the first frame outside nav2_pyif on: the planner author's own code
    first, not the host's call path into it. All of it when every frame is nav2_pyif's (an
    error the host itself raised about what the planner returned)."""
    first = tb
    while first is not None and first.tb_frame.f_code.co_filename.startswith(_INTERNAL_DIR):
        first = first.tb_next
    return first or tb


def _refused_return(exc: BaseException) -> tuple[bool, Any]:
    """(True, what the planner returned) when ``exc`` is a check of results.py refusing a
    planner's return value (each check takes that value as its first argument)."""
    tb = exc.__traceback__
    while tb is not None:
        code = tb.tb_frame.f_code
        if code.co_filename == _RESULTS_FILE and code.co_argcount:
            return True, tb.tb_frame.f_locals.get(code.co_varnames[0])
        tb = tb.tb_next
    return False, None


def _short_traceback(
    exc: BaseException, site: tuple[traceback.StackSummary, str] | None = None
) -> str:
    """The planner's own frames; ``site``: for a refused return value, where it returned."""
    if site is not None:
        stack, note = site
        text = "Traceback (most recent call last):\n" + "".join(stack.format())
        text += "".join(traceback.format_exception_only(type(exc), exc))
        text += f"{note}\n" if note else ""
    else:
        tb = _user_frames(exc.__traceback__)
        text = "".join(traceback.format_exception(type(exc), exc, tb))
    if len(text) <= MAX_TRACEBACK_CHARS:
        return text
    half = MAX_TRACEBACK_CHARS // 2
    return f"{text[:half]}\n... ({len(text) - 2 * half} characters cut) ...\n{text[-half:]}"


class PlannerRuntime:
    """Serves one planner class; one planner instance per client session."""

    def __init__(
        self,
        planner_class: type[PlannerPlugin],
        host_id: str,
        label: str = "",
        logger: logging.Logger | None = None,
    ) -> None:
        self.planner_class = planner_class
        self.plugin_type: PluginType = planner_class.plugin_type
        self.host_id = host_id
        self.label = label or planner_class.__qualname__
        self.log = logger or logging.getLogger("nav2_pyif.server.host")
        self.sessions: dict[str, Session] = {}
        self.max_sessions = MAX_SESSIONS
        self._ended_idle = ThrottledWarning(self.log)  # a configure flood may end many
        # cancel_plan has its own key (handle_cancel), never a call.
        self._served_ops = OPS_BY_PLUGIN[self.plugin_type] - {Op.CANCEL_PLAN}
        self._handlers: dict[Op, Callable[[Session, Request], Body]] = {
            Op.ACTIVATE: self._activate,
            Op.DEACTIVATE: self._deactivate,
            Op.CLEANUP: self._cleanup,
            Op.SET_PARAMETERS: self._set_parameters,
            Op.SET_PLAN: self._set_plan,
            Op.COMPUTE_VELOCITY_COMMANDS: self._compute_velocity_commands,
            Op.SET_SPEED_LIMIT: self._set_speed_limit,
            Op.CANCEL: self._cancel,
            Op.RESET: self._reset,
            Op.CREATE_PLAN: self._create_plan,
            Op.SMOOTH: self._smooth,
            Op.IS_GOAL_REACHED: self._is_goal_reached,
            Op.GET_TOLERANCES: self._get_tolerances,
            Op.CHECK: self._check,
            Op.UPDATE_BOUNDS: self._update_bounds,
            Op.UPDATE_COSTS: self._update_costs,
            Op.MATCH_SIZE: self._match_size,
            Op.ON_RUN: self._on_run,
            Op.ON_CYCLE_UPDATE: self._on_cycle_update,
            Op.ON_ACTION_COMPLETION: self._on_action_completion,
            Op.FIND_PLAN_SEGMENT: self._find_plan_segment,
        }

    # --- entry points -------------------------------------------------------------------
    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        """Request bytes -> reply bytes. Never raises."""
        admitted = self._admit(payload, key_op)
        if isinstance(admitted, bytes):
            return admitted
        request = admitted
        start = time.perf_counter_ns()
        try:
            if request.op is Op.CONFIGURE:
                body = self._configure(request)
            else:
                session = self._session_of(request)
                if isinstance(session, bytes):
                    return session
                body = self._handlers[request.op](session, request)
        except BaseException as exc:  # a planner may raise anything; the host must survive
            return self._exception_reply(request, exc, time.perf_counter_ns() - start)
        return self.encode_ok(request, body, time.perf_counter_ns() - start)

    def _admit(self, payload: bytes, key_op: str | None) -> Request | bytes:
        """The decoded request, if this key serves its op; else the error reply."""
        try:
            request = decode_request(payload)
        except ProtocolError as exc:
            return self._error_reply(peek_seq(payload), exc.error_type, str(exc))
        if key_op is not None and key_op != request.op.value:
            return self._error_reply(
                request.seq,
                ErrorType.BAD_REQUEST,
                f"request op {request.op.value!r} sent to key of op {key_op!r}",
            )
        if request.op not in self._served_ops:
            return self._error_reply(
                request.seq,
                ErrorType.BAD_REQUEST,
                f"{request.op.value} is not an operation of a {self.plugin_type.value} "
                f"(this key serves {self.label})",
            )
        return request

    def _session_of(self, request: Request) -> Session | bytes:
        """The request's session, its costmap updated from the request; else the
        SessionUnknown reply. Raises what decoding the costmap raises."""
        session = self.sessions.get(request.sid)
        if session is None or session.epoch != request.epoch:
            return self._error_reply(
                request.seq,
                ErrorType.SESSION_UNKNOWN,
                f"session {request.sid} epoch {request.epoch} is not known to host "
                f"{self.host_id}; re-send configure",
            )
        session.last_call = time.monotonic()
        if "costmap" in request.body:
            session.context.costmap = Costmap.from_wire(
                request.body["costmap"], session.context.inflation
            )
        return session

    def open_cycle(self, payload: bytes) -> tuple[Request, Session, tuple[Any, ...]] | bytes:
        """A batched cycle's request admitted, its session found (its costmap and inputs
        taken) and its arguments (pose, velocity, goal checker) built; else its error reply."""
        admitted = self._admit(payload, Op.COMPUTE_VELOCITY_COMMANDS.value)
        if isinstance(admitted, bytes):
            return admitted
        try:
            session = self._session_of(admitted)
            if isinstance(session, bytes):
                return session
            return admitted, session, self._cycle_arguments(session, admitted)
        except BaseException as exc:
            return self._exception_reply(admitted, exc, 0)

    def close_cycle(
        self, request: Request, session: Session, pose: Any, result: Any, elapsed_ns: int
    ) -> bytes:
        """A batched cycle's reply from what the planner returned for it. Never raises."""
        try:
            body = self._cycle_body(session, pose, result)
        except BaseException as exc:
            return self._exception_reply(request, exc, elapsed_ns)
        return self.encode_ok(request, body, elapsed_ns)

    def encode_ok(self, request: Request, body: Body, elapsed_ns: int) -> bytes:
        reply = Reply(seq=request.seq, ok=True, host=self.host_id, body=body, compute_ns=elapsed_ns)
        try:
            # compute_velocity_commands' body comes from checked_twist_stamped: floats, in order.
            return encode_reply(
                reply, request.op, validate=request.op is not Op.COMPUTE_VELOCITY_COMMANDS
            )
        except ProtocolError as exc:
            return self._error_reply(
                request.seq,
                generic_error(self.plugin_type).error_type,
                f"{request.op.value} produced an unencodable reply: {exc}",
            )

    def handle_cancel(self, payload: bytes) -> bytes:
        """``cancel_plan``: flag a running create_plan. Thread-safe; answered at once."""
        try:
            request = decode_request(payload)
        except ProtocolError as exc:
            return self._error_reply(peek_seq(payload), exc.error_type, str(exc))
        if request.op is not Op.CANCEL_PLAN:
            return self._error_reply(
                request.seq, ErrorType.BAD_REQUEST, f"{request.op.value} sent to the cancel key"
            )
        session = self.sessions.get(request.sid)
        accepted = bool(
            session is not None
            and session.epoch == request.epoch
            and session.running_seq == request.body["target_seq"]
        )
        if accepted and session is not None:
            session.cancel_requested.set()
        reply = Reply(request.seq, True, self.host_id, body={"accepted": accepted})
        return encode_reply(reply, Op.CANCEL_PLAN)

    def close(self) -> None:
        """Clean up every session's planner (host shutdown)."""
        for session in list(self.sessions.values()):
            try:
                session.planner.cleanup()
            except BaseException:
                self.log.exception("%s: cleanup of session %s failed", self.label, session.sid)
        self.sessions.clear()

    # --- replies ------------------------------------------------------------------------
    def _error_reply(
        self,
        seq: int,
        error_type: ErrorType,
        message: str,
        tb: str = "",
        python_type: str = "",
        compute_ns: int = 0,
    ) -> bytes:
        return error_reply(seq, self.host_id, error_type, message, tb, python_type, compute_ns)

    def _exception_reply(
        self, request: Request, exc: BaseException, elapsed: int, *, log: bool = True
    ) -> bytes:
        if isinstance(exc, Nav2Error):
            error_type = exc.error_type
            message = str(exc) or type(exc).__name__
        else:
            error_type = (
                INVALID_ERROR[self.plugin_type]
                if request.op is Op.CONFIGURE
                else generic_error(self.plugin_type).error_type
            )
            message = "".join(traceback.format_exception_only(type(exc), exc)).strip()
        message = f"{self.label}.{request.op.value}: {message}"
        tb = _short_traceback(exc, self._return_site(request, exc))
        if log:  # a batched call's error is logged once, not once per robot
            self.log.error(
                "%s failed [%s]: %s\n%s", request.op.value, error_type.value, message, tb
            )
        return self._error_reply(request.seq, error_type, message, tb, _qualname(exc), elapsed)

    def exception_reply(
        self, request: Request, exc: BaseException, elapsed: int, *, log: bool = True
    ) -> bytes:
        """The typed error reply to ``request`` for ``exc`` (a batched call's errors)."""
        return self._exception_reply(request, exc, elapsed, log=log)

    def _return_site(
        self, request: Request, exc: BaseException
    ) -> tuple[traceback.StackSummary, str] | None:
        """Where the planner returned the value a check refused (None: not such an error,
        or its source is unknown)."""
        refused, returned = _refused_return(exc)
        session = self.sessions.get(request.sid)
        if not refused or session is None:
            return None
        try:  # the op is named after the planner's method (cancel, create_plan, check, ...)
            return return_site(session.planner, request.op.value, returned)
        except Exception:  # an error reply must never fail: the host's frames then
            return None

    # --- operations ---------------------------------------------------------------------
    def _configure(self, request: Request) -> Body:
        body = request.body
        if body["plugin_type"] != self.plugin_type.value:
            try:
                invalid = NAV2_EXCEPTIONS[INVALID_ERROR[PluginType(body["plugin_type"])].value]
            except ValueError:
                invalid = generic_error(self.plugin_type)
            raise invalid(
                f"the Nav2 plugin is a {body['plugin_type']} but this key serves "
                f"{self.label}, a {self.plugin_type.value}"
            )
        previous = self.sessions.pop(request.sid, None)
        if previous is not None:
            self._safe_cleanup(previous)
        now = time.monotonic()
        idle = session_to_end(self.sessions, request.sid, now, self.max_sessions)
        if idle is not None:
            del self.sessions[idle.sid]
            self._safe_cleanup(idle)
            self._ended_idle(
                "%s: session %s (%s) ended, idle for %.0f s, to make room for session %s: "
                "the planner keeps at most %d",
                self.label,
                idle.sid[:8],
                idle.context.node_name,
                now - idle.last_call,
                request.sid[:8],
                self.max_sessions,
            )
        planner = self.planner_class()
        nav2_params = body.get("nav2_params") or {}
        context = PluginContext(
            name=body["name"],
            node_name=body["node"],
            global_frame=body["global_frame"],
            robot_base_frame=body["robot_base_frame"],
            costmap=Costmap.from_wire(body["costmap"], Inflation.from_params(nav2_params)),
            params=Parameters(body["params"]),
            logger=logging.getLogger(f"nav2_pyif.planner.{body['name']}"),
            nav2_params=nav2_params,
        )
        planner._attach(context)
        if isinstance(planner, Controller) and planner.debug_outputs:
            check_declared(planner.debug_outputs)  # context.debug: set by _attach
        planner.configure()
        if isinstance(planner, Controller):
            warm_serialization()  # in configure, not in its first cycle with an input
        settle_heap()
        context.params.on_change(planner.on_parameters_changed)
        self.sessions[request.sid] = Session(request.sid, request.epoch, planner, context)
        self.log.info(
            "%s: session %s configured (epoch %d) for %s/%s",
            self.label,
            request.sid[:8],
            request.epoch,
            body["node"],
            body["name"],
        )
        reply: Body = {"declared": context.params.declared(), "planner": self.label}
        undeclared = context.params.undeclared()
        if undeclared:
            self.log.warning(
                "%s: session %s: parameters given but never declared, ignored: %s; %s",
                self.label,
                request.sid[:8],
                "; ".join(undeclared.values()),
                declares(reply["declared"]),
            )
            reply["undeclared"] = undeclared
        if context.debug.declared:
            reply["debug_outputs"] = dict(context.debug.declared)
        return reply

    def _safe_cleanup(self, session: Session) -> None:
        try:
            session.planner.cleanup()
        except BaseException:
            self.log.exception("%s: cleanup of replaced session %s failed", self.label, session.sid)

    def _activate(self, session: Session, request: Request) -> Body:
        session.planner.activate()
        session.active = True
        return {}

    def _deactivate(self, session: Session, request: Request) -> Body:
        session.active = False
        session.planner.deactivate()
        return {}

    def _cleanup(self, session: Session, request: Request) -> Body:
        try:
            session.planner.cleanup()
        finally:
            self.sessions.pop(session.sid, None)
        return {}

    def _set_parameters(self, session: Session, request: Request) -> Body:
        _, rejected = session.context.params.update(request.body["params"])
        return {"rejected": rejected}

    def _set_plan(self, session: Session, request: Request) -> Body:
        if isinstance(session.planner, PathHandler):
            plan = Plan.from_wire(request.body["path"])
            if not np.isfinite(plan.array).all():
                raise InvalidPath("the plan sent to set_plan has non-finite values")
            session.planner.set_plan(plan)
            return {}
        follow_plan(session.planner, request.body["path"], request.body.get("goal"))
        return {}

    def _find_plan_segment(self, session: Session, request: Request) -> Body:
        handler = session.planner
        assert isinstance(handler, PathHandler)
        segment = handler.find_plan_segment(pose_from_wire(request.body["pose"]))
        start, end = checked_segment(segment, len(handler.plan))
        return {"start": start, "end": end}

    def _compute_velocity_commands(self, session: Session, request: Request) -> Body:
        pose, velocity, checker = self._cycle_arguments(session, request)
        result = session.planner.compute_velocity_commands(pose, velocity, checker)  # type: ignore[attr-defined]
        return self._cycle_body(session, pose, result)

    def _cycle_arguments(self, session: Session, request: Request) -> tuple[Any, Any, Any]:
        """(pose, velocity, goal checker) of a cycle; the session's inputs and debug wishes
        taken from the request first."""
        body, context = request.body, session.context
        if "plan" in body:  # Lyrical: the plan Nav2 transformed, when it changed
            follow_plan(session.planner, body["plan"], body.get("goal"), in_cycle=True)
        elif "goal" in body:
            session.planner.global_goal = pose_from_wire(body["goal"])  # type: ignore[attr-defined]
        checker = body.get("goal_checker")
        context.inputs.update(body.get("inputs", []))
        context.debug.begin(body.get("debug_wanted", ()))
        return (
            pose_from_wire(body["pose"]),
            twist_from_list(body["velocity"]),
            GoalTolerances.from_wire(checker) if checker is not None else None,
        )

    def _cycle_body(self, session: Session, pose: Any, result: Any) -> Body:
        context = session.context
        values = checked_twist_stamped(result, "compute_velocity_commands")
        header = result.header
        reply: Body = {
            "cmd_vel": {
                "frame_id": header.frame_id or context.robot_base_frame,
                "stamp_ns": stamp_to_ns(header.stamp),
                "twist": values,
            }
        }
        debug = context.debug.collect(context.global_frame, pose.header.stamp)
        if debug:
            reply["debug"] = debug
        return reply

    def _set_speed_limit(self, session: Session, request: Request) -> Body:
        body = request.body
        session.planner.set_speed_limit(body["speed_limit"], body["percentage"])  # type: ignore[attr-defined]
        return {}

    def _cancel(self, session: Session, request: Request) -> Body:
        done = session.planner.cancel()  # type: ignore[attr-defined]
        return {"cancelled": checked_bool(done, "cancel", generic_error(self.plugin_type))}

    def _reset(self, session: Session, request: Request) -> Body:
        session.planner.reset()  # type: ignore[attr-defined]
        return {}

    def _create_plan(self, session: Session, request: Request) -> Body:
        planner = session.planner
        assert isinstance(planner, GlobalPlanner)
        start = pose_from_wire(request.body["start"])
        goal = pose_from_wire(request.body["goal"])
        viapoints = request.body.get("viapoints")
        planner.viapoints = Plan.from_wire(viapoints).poses if viapoints else ()
        session.cancel_requested.clear()
        session.running_seq = request.seq
        try:
            result = planner.create_plan(start, goal, session.cancel_requested.is_set)
        finally:
            session.running_seq = None
        plan = checked_plan(
            result, session.context.global_frame, request.body["start"]["stamp_ns"], "create_plan"
        )
        return {"path": plan.to_wire()}

    def _smooth(self, session: Session, request: Request) -> Body:
        smoother = session.planner
        assert isinstance(smoother, Smoother)
        wire = request.body["path"]
        path = Plan.from_wire(wire)
        if not np.isfinite(path.array).all():
            raise InvalidPath("the path sent to smooth has non-finite values")
        result = smoother.smooth(path, request.body["max_time"])
        smoothed, completed = checked_smoothed(result, wire["frame_id"], wire["stamp_ns"])
        return {"path": smoothed.to_wire(), "was_completed": completed}

    def _is_goal_reached(self, session: Session, request: Request) -> Body:
        checker = session.planner
        assert isinstance(checker, GoalChecker)
        body, frame = request.body, session.context.global_frame
        # Lyrical's isGoalXYReached travels as is_goal_reached with xy_only
        check = checker.is_goal_xy_reached if body.get("xy_only") else checker.is_goal_reached
        reached = check(
            pose_from_wire({"frame_id": frame, "stamp_ns": 0, "pose": body["pose"]}).pose,
            pose_from_wire({"frame_id": frame, "stamp_ns": 0, "pose": body["goal"]}).pose,
            twist_from_list(body["velocity"]),
        )
        return {
            "reached": checked_bool(reached, "is_goal_reached", generic_error(self.plugin_type))
        }

    def _get_tolerances(self, session: Session, request: Request) -> Body:
        checker = session.planner
        assert isinstance(checker, GoalChecker)
        return tolerances_to_wire(checker.get_tolerances())

    def _check(self, session: Session, request: Request) -> Body:
        checker = session.planner
        assert isinstance(checker, ProgressChecker)
        progress = checker.check(pose_from_wire(request.body["pose"]))
        return {"making_progress": checked_bool(progress, "check", generic_error(self.plugin_type))}

    def _update_bounds(self, session: Session, request: Request) -> Body:
        layer = session.planner
        assert isinstance(layer, CostmapLayer)
        b = request.body
        given = (b["min_x"], b["min_y"], b["max_x"], b["max_y"])
        grown = layer.update_bounds(b["robot_x"], b["robot_y"], b["robot_yaw"], given)
        min_x, min_y, max_x, max_y = checked_bounds(grown)
        return {"min_x": min_x, "min_y": min_y, "max_x": max_x, "max_y": max_y}

    def _update_costs(self, session: Session, request: Request) -> Body:
        layer = session.planner
        assert isinstance(layer, CostmapLayer)
        b = request.body
        window = LayerWindow(
            b["min_i"], b["min_j"], b["max_i"], b["max_j"],
            b["origin_x"], b["origin_y"], b["resolution"],
        )  # fmt: skip
        costs, combine = checked_layer_costs(layer.update_costs(window), window.shape)
        rows, cols = window.shape
        return {"width": cols, "height": rows, "costs": costs, "combine": combine}

    def _match_size(self, session: Session, request: Request) -> Body:
        layer = session.planner
        assert isinstance(layer, CostmapLayer)
        b = request.body
        layer.match_size(b["size_x"], b["size_y"], b["resolution"], b["origin_x"], b["origin_y"])
        return {}

    def _on_run(self, session: Session, request: Request) -> Body:
        behavior = session.planner
        assert isinstance(behavior, Behavior)
        body = request.body
        behavior.pose = pose_from_wire(body["pose"])
        result = behavior.on_run(Command(body["action"], body["command"]))
        reply = checked_step(result, "on_run", session.context.robot_base_frame)
        if reply["status"] == Status.RUNNING.value:
            raise generic_error(self.plugin_type)(
                "on_run returned RUNNING; it returns SUCCEEDED (start cycling) or FAILED"
            )
        reply.pop("cmd_vel", None)  # on_run's answer is only a status (TimedBehavior's)
        reply.pop("feedback", None)
        return reply

    def _on_cycle_update(self, session: Session, request: Request) -> Body:
        behavior = session.planner
        assert isinstance(behavior, Behavior)
        behavior.pose = pose = pose_from_wire(request.body["pose"])
        result = behavior.on_cycle_update(pose, request.body["elapsed"])
        return checked_step(result, "on_cycle_update", session.context.robot_base_frame)

    def _on_action_completion(self, session: Session, request: Request) -> Body:
        behavior = session.planner
        assert isinstance(behavior, Behavior)
        behavior.on_action_completion(request.body["status"], request.body["elapsed"])
        return {}


def error_reply(
    seq: int,
    host_id: str,
    error_type: ErrorType,
    message: str,
    tb: str = "",
    python_type: str = "",
    compute_ns: int = 0,
) -> bytes:
    """An encoded error reply (its body schema does not depend on the op)."""
    error = ErrorInfo(error_type.value, message, tb, python_type)
    reply = Reply(seq=seq, ok=False, host=host_id, error=error, compute_ns=compute_ns)
    return encode_reply(reply, Op.ACTIVATE)


def peek_seq(payload: bytes) -> int:
    """Best-effort seq of an undecodable request, so the client can match the error."""
    try:
        raw = unpack_bounded(payload)
        seq = raw.get("seq", 0) if isinstance(raw, dict) else 0
        return seq if isinstance(seq, int) and not isinstance(seq, bool) and seq >= 0 else 0
    except Exception:
        return 0
