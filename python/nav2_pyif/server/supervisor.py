"""Crash isolation: a planner runs in a worker process watched by the host.

- A worker that dies (segfault, OOM kill, ``os._exit``, ``kill -9``) is restarted and every
  session is restored on the new one from the journal; meanwhile calls are answered at once
  with a typed ``Unavailable`` error naming the cause, never left hanging.
- A worker that crash-loops is restarted with exponential back-off, and says so.
- A call that overruns its deadline is answered with Unavailable (the plugin's host failure); a
  worker that does not come back within the grace period (stuck in native code) is killed
  and restarted.
- Where it crashed or hangs (``stacks``): the Python stack a dying worker leaves, or the one a
  late worker dumps when asked, is logged and sent as the traceback of the errors that say
  so.
- ``reload`` swaps in a new planner (or a fresh import of the same one) on a live key: the
  new worker is loaded and given every session while the old one keeps serving, then the two
  are swapped between two calls.
"""

from __future__ import annotations

import contextlib
import logging
import math
import multiprocessing
import select
import signal
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

import msgpack
from nav2_pyif_protocol.bounded import unpack_bounded
from nav2_pyif_protocol.constants import ErrorType, PluginType
from nav2_pyif_protocol.schema import OP_TIMEOUT, SMOOTH_GRACE_S

from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.batch_runtime import BATCH_OP, CYCLE_OP
from nav2_pyif.server.frames import FramedPipe
from nav2_pyif.server.journal import Journal, Snapshot, replay
from nav2_pyif.server.runtime import error_reply, peek_seq
from nav2_pyif.server.spec import PlannerSpec
from nav2_pyif.server.stacks import StackFile
from nav2_pyif.server.worker import LOAD_ERROR, worker_main

log = logging.getLogger("nav2_pyif.server.supervisor")
_SPAWN = multiprocessing.get_context("spawn")  # never fork a process that runs Zenoh threads


# Each op's deadline field by its plain name: Deadlines.of runs on every call, and Enum.value
# costs an attribute lookup through a descriptor each time (schema.py OP_TIMEOUT: the classes
# are named after Deadlines' fields).
_DEADLINE_OF = {op.value: timeout.value for op, timeout in OP_TIMEOUT.items()}


@dataclass(frozen=True)
class Deadlines:
    """Seconds the host lets a planner method run before answering with a timeout."""

    call: float = 1.0  # control-loop ops
    configure: float = 60.0
    plan: float = 30.0  # create_plan and smooth
    lifecycle: float = 10.0
    hang_grace: float = 3.0  # then a worker still busy is killed and restarted

    def of(self, op: str, payload: bytes = b"") -> float:
        """``op``'s deadline; a ``smooth`` request's ``max_time`` and SMOOTH_GRACE_S when
        longer, as the plugin waits that long for the smoother it gave that time."""
        deadline: float = getattr(self, _DEADLINE_OF.get(op, "call"))
        if op == "smooth":
            deadline = max(deadline, _smooth_max_time(payload) + SMOOTH_GRACE_S)
        return deadline


def _smooth_max_time(payload: bytes) -> float:
    """A smooth request's max_time, or 0 where it has none a worker would accept."""
    try:
        max_time = unpack_bounded(payload)["body"]["max_time"]
    except Exception:
        return 0.0
    ok = isinstance(max_time, (int, float)) and not isinstance(max_time, bool)
    return float(max_time) if ok and math.isfinite(max_time) and max_time > 0 else 0.0


def _dumped(stack: str, when: str) -> str:
    return f"Stack of the planner worker {when}:\n{stack}" if stack else ""


class WorkerDied(Exception):
    pass


def describe_exit(code: int | None) -> str:
    if code is None:
        return "still running"
    if code < 0:
        try:
            return f"killed by signal {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exited with code {code}"


class Worker:
    """One worker process and its two pipes: calls (framed, the hot path) and cancels."""

    def __init__(
        self,
        spec: PlannerSpec,
        host_id: str,
        memory_limit: int | None,
        log_level: str,
        quiet: bool = False,
    ) -> None:
        calls, child_calls = _SPAWN.Pipe()
        self.calls = FramedPipe(calls)
        self.cancels, child_cancels = _SPAWN.Pipe()
        self.stacks = StackFile()
        self.process = _SPAWN.Process(
            target=worker_main,
            name=f"planner-worker:{spec.key}",
            daemon=True,
            args=(
                child_calls,
                child_cancels,
                spec,
                host_id,
                memory_limit,
                log_level,
                quiet,
                self.stacks.path,
            ),
        )
        self.process.start()
        child_calls.close()
        child_cancels.close()
        self.cancel_lock = threading.Lock()
        # Waiting for a reply on a poll object kept for the worker's life: Connection.poll
        # builds a selector on every call (about 2.5 µs of Python per call, measured hot).
        self._replies = select.poll()
        self._replies.register(self.calls.fileno(), select.POLLIN)

    @property
    def pid(self) -> int | None:
        return self.process.pid

    def exit_description(self) -> str:
        self.process.join(0.5)
        return describe_exit(self.process.exitcode)

    def stack(self, *, dump: bool = False) -> str:
        """The Python stack the worker left since the last call (a fatal signal's, an
        ``os._exit``'s); with ``dump``, a live worker's stack of every thread, now."""
        if dump and self.process.is_alive() and self.process.pid is not None:
            return self.stacks.dump(self.process.pid)
        return self.stacks.read_new()

    def wait_loaded(self, timeout: float) -> PluginType:
        try:
            reply = self._receive(timeout)
        finally:
            self.stacks.unlink()  # opened by the worker by now, or never
        if reply is None:
            self.stop()
            raise PlannerLoadError(f"planner worker did not load within {timeout:.0f} s")
        kind, detail = msgpack.unpackb(reply)
        if kind == LOAD_ERROR:
            self.process.join(5)  # it exits on its own
            self.kill()
            raise PlannerLoadError(detail)
        return PluginType(detail)

    def call(self, op: str, payload: bytes, timeout: float) -> bytes | None:
        """The reply, or None when ``timeout`` passed first. Raises WorkerDied."""
        try:
            self.calls.send(op.encode() + b"\0" + payload)
        except OSError as exc:  # BrokenPipeError: the worker is gone
            raise WorkerDied(self.exit_description()) from exc
        return self._receive(timeout)

    def _receive(self, timeout: float) -> bytes | None:
        # The pipe alone (not pipe + process sentinel): one fd, cheaper on every call; a dead
        # worker's pipe reads EOF (POLLHUP), so deaths are still seen at once.
        if not self.calls.pending() and not self._replies.poll(max(0, math.ceil(timeout * 1000))):
            if not self.process.is_alive():
                raise WorkerDied(self.exit_description())
            return None
        try:
            return self.calls.recv()
        except (EOFError, OSError):
            raise WorkerDied(self.exit_description()) from None

    def drain(self) -> bool:
        """Consume a late reply, if one arrived; True when the worker is free again."""
        try:
            if self.calls.pending() or self._replies.poll(0):
                self.calls.recv()
                return True
        except (EOFError, OSError):
            pass
        return False

    def cancel(self, payload: bytes, timeout: float = 1.0) -> bytes | None:
        with self.cancel_lock:
            try:
                self.cancels.send_bytes(payload)
                if self.cancels.poll(timeout):
                    return self.cancels.recv_bytes()
            except (EOFError, OSError):
                pass
        return None

    def alive(self) -> bool:
        return self.process.is_alive()

    def stop(self, grace: float = 2.0) -> None:
        if self.process.is_alive():
            with contextlib.suppress(OSError):
                self.calls.send(b"")
            self.process.join(grace)
        if self.process.is_alive():
            self.process.kill()
            self.process.join(5)
        for conn in (self.calls, self.cancels):
            conn.close()
        self.stacks.remove()

    def kill(self) -> None:
        if self.process.is_alive():
            self.process.kill()
        self.process.join(5)
        self.stacks.remove()


class SupervisedPlanner:
    """The interface of PlannerRuntime (handle, handle_cancel, close), backed by a worker."""

    isolation = "process"

    def __init__(
        self,
        spec: PlannerSpec,
        host_id: str,
        *,
        deadlines: Deadlines | None = None,
        memory_limit: int | None = None,
        log_level: str = "INFO",
        crash_window: float = 10.0,
        crash_threshold: int = 3,
        max_backoff: float = 30.0,
    ) -> None:
        self.spec = spec
        self.host_id = host_id
        self.deadlines = deadlines or Deadlines()
        self.memory_limit = memory_limit
        self.log_level = log_level
        self.crash_window, self.crash_threshold = crash_window, crash_threshold
        self.max_backoff = max_backoff
        self.journal = Journal()
        self.swapped_at = 0.0  # unix time of the last hot swap
        self.plugin_type = PluginType.CONTROLLER
        self.worker: Worker | None = None
        self.reason = "starting"
        self.reason_stack = ""  # where the planner crashed or hangs, while ``reason`` holds
        self.overrun_since: float | None = None
        self.deaths: deque[float] = deque(maxlen=50)
        self.restarts = 0
        self._lock = threading.RLock()  # one call at a time; swaps happen between calls
        self._wake = threading.Event()
        self._closing = False
        self._monitor = threading.Thread(
            target=self._watch, name=f"supervisor:{spec.key}", daemon=True
        )

    @property
    def label(self) -> str:
        return self.spec.describe()

    # --- lifecycle ---------------------------------------------------------------------
    def start(self) -> SupervisedPlanner:
        """Start the first worker; a planner that cannot load raises PlannerLoadError."""
        worker = self._new_worker(self.spec)
        self.plugin_type = worker.wait_loaded(self.deadlines.configure)
        self.worker = worker
        self._set_reason("")
        self._monitor.start()
        # Not "serving" yet: a signal may stop the host before it serves; the host says when.
        # Said for each, as planners load in parallel: a start-up that takes too long shows
        # which planner is still importing (the runner names it).
        log.info("%s: loaded %s (worker %s)", self.spec.key, self.label, worker.pid)
        return self

    @property
    def where(self) -> str:
        """Where the planner runs, for the host's log."""
        worker = self.worker
        return f"worker {worker.pid}" if worker is not None else "no worker"

    def close(self) -> None:
        self._closing = True
        self._wake.set()
        if self._monitor.is_alive():  # a restart under way stops its new worker
            self._monitor.join(10.0)
        with self._lock:
            if self.worker is not None:
                self.worker.stop()
                self.worker = None

    def _new_worker(self, spec: PlannerSpec, *, quiet: bool = False) -> Worker:
        return Worker(spec, self.host_id, self.memory_limit, self.log_level, quiet)

    # --- calls -------------------------------------------------------------------------
    def handle(self, payload: bytes, key_op: str | None = None) -> bytes:
        op = key_op or ""
        if op not in _DEADLINE_OF:  # the worker pipe reads op names as commands (BATCH_OP)
            return self._error(payload, ErrorType.BAD_REQUEST, f"no operation {op!r}")
        return self._exchange(
            op,
            payload,
            lambda kind, message, tb: self._error(payload, kind, message, tb),
            lambda reply: self.journal.note(op, payload, reply),
        )

    def handle_batch(self, payloads: list[bytes]) -> list[bytes]:
        """Control cycles of several sessions in one worker call (batch_runtime): one reply
        each, in order. A crash or hang fails each of them with Unavailable, as one call's."""

        def failed(kind: ErrorType, message: str, tb: str) -> bytes:
            return msgpack.packb([self._error(p, kind, message, tb) for p in payloads])

        def note(reply: bytes) -> None:  # the costmap updates the cycles carried
            for payload, answer in zip(payloads, msgpack.unpackb(reply), strict=True):
                self.journal.note(CYCLE_OP, payload, answer)

        replies: list[bytes] = msgpack.unpackb(
            self._exchange(BATCH_OP, msgpack.packb(payloads), failed, note)
        )
        return replies

    def _exchange(
        self,
        op: str,
        payload: bytes,
        error: Callable[[ErrorType, str, str], bytes],
        note: Callable[[bytes], None],
    ) -> bytes:
        """The worker's reply to one call, or ``error(type, message, traceback)``'s when the
        worker is unavailable, dies during the call or overruns its deadline. ``note``: the
        reply recorded in the journal, under the lock (a hot swap replays between calls)."""
        with self._lock:
            worker = self.worker
            if worker is not None and self.overrun_since is not None and worker.drain():
                self._set_reason("")  # the late call finished
                self.overrun_since = None
            if worker is None or self.reason:
                return error(
                    ErrorType.UNAVAILABLE,
                    f"{self.spec.key}: planner unavailable: {self.reason}",
                    self.reason_stack,
                )
            deadline = self.deadlines.of(op, payload)
            try:
                reply = worker.call(op, payload, deadline)
            except WorkerDied as died:
                self._on_death(worker, f"{died} during {op}")
                return error(
                    ErrorType.UNAVAILABLE,
                    f"{self.spec.key}: planner worker {died} during {op}; "
                    "restarting it and restoring every session",
                    self.reason_stack,
                )
            if reply is None:
                self.overrun_since = time.monotonic()
                # Where it is stuck, asked now: it may never come back to say.
                stack = _dumped(worker.stack(dump=True), "when it overran its deadline")
                self._set_reason(
                    f"busy: {op} overran its {deadline:g} s deadline; the worker is "
                    f"restarted unless it returns within {self.deadlines.hang_grace:g} s",
                    stack,
                )
                log.warning(
                    "%s: %s.%s overran its %g s deadline; where it is:\n%s",
                    self.spec.key,
                    self.label,
                    op,
                    deadline,
                    stack or "(no stack: the worker did not answer SIGUSR1)",
                )
                self._wake.set()
                # Unavailable, not the plugin type's TimedOut: the hang is the host's to
                # handle (it restarts the worker), and the plugin turns Unavailable into
                # the exception Nav2 recovers from; ControllerTimedOut would end the
                # navigation (constants.HOST_FAILURE_ERROR).
                return error(
                    ErrorType.UNAVAILABLE,
                    f"{self.label}.{op} overran its {deadline:g} s deadline",
                    stack,
                )
            note(reply)
            return reply

    def handle_cancel(self, payload: bytes) -> bytes:
        worker = self.worker  # no lock: a cancel must get through while a call runs
        reply = worker.cancel(payload) if worker is not None else None
        if reply is None:
            return self._error(payload, ErrorType.UNAVAILABLE, "planner worker unavailable")
        return reply

    def _error(self, payload: bytes, error_type: ErrorType, message: str, tb: str = "") -> bytes:
        return error_reply(peek_seq(payload), self.host_id, error_type, message, tb)

    def _set_reason(self, reason: str, stack: str = "") -> None:
        """Why calls are answered Unavailable ("" : they are served), and where the planner
        crashed or hangs, sent with each of those answers."""
        self.reason, self.reason_stack = reason, stack

    # --- restarts ------------------------------------------------------------------------
    def _on_death(self, worker: Worker, cause: str, *, dump: bool = False) -> None:
        """Called with the lock held. ``dump``: the worker is alive (hung); its stack is
        asked for before it is killed."""
        if self.worker is not worker:
            return
        stack = worker.stack(dump=dump)
        if dump:
            stack = _dumped(stack, "before it was killed")
        log.error(
            "%s: planner worker %s %s; restarting it%s",
            self.spec.key,
            worker.pid,
            cause,
            f"; where it was:\n{stack}" if stack else "",
        )
        worker.kill()
        self.worker, self.overrun_since = None, None
        self.deaths.append(time.monotonic())
        self._set_reason(f"planner worker {cause}; restarting", stack or self.reason_stack)
        self._wake.set()

    def _backoff(self) -> float:
        now = time.monotonic()
        recent = [t for t in self.deaths if now - t < self.crash_window]
        if len(recent) < self.crash_threshold:
            return 0.0
        return float(min(self.max_backoff, 2.0 ** (len(recent) - self.crash_threshold)))

    def _watch(self) -> None:
        """Restart dead workers, kill hung ones, notice deaths between calls."""
        while not self._closing:
            self._wake.wait(0.2)
            self._wake.clear()
            if self._closing:
                return
            with self._lock:
                worker = self.worker
                if worker is not None and not worker.alive():
                    self._on_death(worker, worker.exit_description() + " between calls")
                    worker = None
                if (
                    worker is not None
                    and self.overrun_since is not None
                    and time.monotonic() - self.overrun_since > self.deadlines.hang_grace
                ):
                    if worker.drain():
                        self.overrun_since = None
                        self._set_reason("")
                    else:
                        self._on_death(
                            worker, "stayed stuck past its deadline and was killed", dump=True
                        )
                        worker = None
                needs_restart = self.worker is None
            if needs_restart:
                self._restart()

    def _restart(self) -> None:
        delay = self._backoff()
        if delay:
            recent = sum(1 for t in self.deaths if time.monotonic() - t < self.crash_window)
            with self._lock:
                self.reason = (  # the stack of the last death stays with it
                    f"crash-looping: the worker died {recent} times in "
                    f"{self.crash_window:g} s; next restart in {delay:g} s"
                )
            log.error("%s: %s", self.spec.key, self.reason)
            if self._sleep(delay):
                return
        worker = self._new_worker(self.spec, quiet=True)  # its warnings were logged at start
        try:
            worker.wait_loaded(self.deadlines.configure)
            self._replay(worker, self.journal.snapshot())
        except (PlannerLoadError, WorkerDied) as exc:
            worker.kill()
            self.deaths.append(time.monotonic())
            with self._lock:
                self._set_reason(f"restart failed: {exc}")
            log.error("%s: restart failed: %s", self.spec.key, exc)
            self._wake.set()
            return
        with self._lock:  # no state changed meanwhile: calls were answered Unavailable
            if self._closing:
                worker.stop()
                return
            self.worker, self.restarts = worker, self.restarts + 1
            self._set_reason("")
        log.warning(
            "%s: worker %s restarted, %d session(s) restored",
            self.spec.key,
            worker.pid,
            len(self.journal),
        )

    def _sleep(self, seconds: float) -> bool:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            if self._closing:
                return True
            time.sleep(0.05)
        return False

    def _replay(self, worker: Worker, snapshot: Snapshot) -> None:
        """Tell a restarted ``worker`` what each session told the planner. A session whose
        replay fails is dropped from the journal: its plugin gets SessionUnknown and re-sends
        its state."""
        for sid, op, reason in replay(snapshot, self._caller(worker)):
            log.warning(
                "%s: could not restore session %s (%s failed: %s)",
                self.spec.key,
                sid[:8],
                op,
                reason,
            )
            self.journal.forget(sid)

    def _caller(self, worker: Worker) -> Callable[[str, bytes], bytes | None]:
        return lambda op, payload: worker.call(op, payload, self.deadlines.of(op, payload))

    # --- hot swap ----------------------------------------------------------------------
    def reload(self, spec: PlannerSpec | None = None, allow_type_change: bool = False) -> str:
        """Swap in ``spec`` (default: a fresh import of the current planner) on this live
        key. All or nothing: the new worker must load and take every live session (configure,
        activate, parameters, plan, speed limit); otherwise PlannerLoadError says why and the
        old worker keeps serving every session."""
        new_spec = spec or self.spec
        worker = self._new_worker(new_spec)
        old = self.worker

        def swap() -> None:  # called with the lock held, between two calls
            nonlocal old
            old, self.worker = self.worker, worker
            self.spec, self.plugin_type = new_spec, plugin_type
            self.swapped_at = time.time()
            self.overrun_since = None
            self._set_reason("")

        try:
            plugin_type = worker.wait_loaded(self.deadlines.configure)
            carried = self.journal.hand_over(
                self._caller(worker),
                (new_spec.describe(), plugin_type),
                self.plugin_type,
                self._lock,
                swap,
                allow_type_change,
            )
        except (PlannerLoadError, WorkerDied) as exc:
            worker.kill()
            raise PlannerLoadError(f"reload refused, still serving {self.label}: {exc}") from exc
        if old is not None:
            old.stop()
        message = (
            f"{self.spec.key}: now serving {new_spec.describe()} "
            f"(worker {worker.pid}, {carried} session(s) carried over)"
        )
        return message  # the host logs it, once, whoever asked (SIGHUP or a remote reload)
