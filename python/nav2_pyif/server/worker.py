"""The worker process: loads one planner and answers calls from its supervisor over a pipe.

Call-pipe messages (frames.FramedPipe, length-prefixed): supervisor -> worker ``op NUL
request-bytes`` (empty: exit); worker -> supervisor, first a load report (msgpack ``["loaded",
plugin_type]`` or ``["load_error", message]``), then one reply per call (a batch of control
cycles, op ``batch_runtime.BATCH_OP``: a msgpack list of requests, a list of replies).
Cancellations arrive on a second pipe and are answered by a thread, while the main thread may
be busy in the planner.
"""

from __future__ import annotations

import logging
import os
import signal
import sys
import threading
from multiprocessing.connection import Connection

import msgpack

from nav2_pyif.common.planner_output import MarkedStream, print_marker
from nav2_pyif.server import stacks
from nav2_pyif.server.batch_runtime import BATCH_OP, handle_batch
from nav2_pyif.server.frames import FramedPipe
from nav2_pyif.server.runtime import PlannerRuntime
from nav2_pyif.server.spec import PlannerSpec

LOADED, LOAD_ERROR = "loaded", "load_error"


def _limit_memory(limit_bytes: int | None) -> None:
    """An address-space cap: a memory hog gets MemoryError (a typed error), not the OOM
    killer's attention for the whole machine."""
    if limit_bytes:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))


def _serve_cancels(cancels: Connection, runtime: list[PlannerRuntime]) -> None:
    """Answer cancellations; when the host's end closes (it stopped us, or died, even by
    SIGKILL), exit at once, whatever the planner is doing: no worker outlives its host."""
    while True:
        try:
            payload = cancels.recv_bytes()
        except (EOFError, OSError):
            stacks.real_exit(0)
        cancels.send_bytes(runtime[0].handle_cancel(payload))


def worker_main(
    calls: Connection,
    cancels: Connection,
    spec: PlannerSpec,
    host_id: str,
    memory_limit: int | None,
    log_level: str,
    quiet: bool = False,
    stack_path: str | None = None,
) -> None:
    logging.basicConfig(
        level=log_level,
        format=f"[%(asctime)s] [%(levelname)s] [worker {os.getpid()}] [%(name)s] %(message)s",
    )
    # The planner's print() output, marked with its key: several planners share the host's
    # stderr (logging's handler keeps the unmarked stream it was given above).
    sys.stdout = MarkedStream(sys.stdout, print_marker(spec.key))
    sys.stderr = MarkedStream(sys.stderr, print_marker(spec.key))
    if stack_path is not None:
        stacks.install(stack_path)  # where it crashed or hangs, for the supervisor
    # Ctrl-C and a terminal's hangup reach the whole process group; they are the host's to
    # act on (stop, reload), and it stops its workers itself.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    pipe = FramedPipe(calls)
    runtime: list[PlannerRuntime] = []  # set once loaded; cancels only come after that
    threading.Thread(target=_serve_cancels, args=(cancels, runtime), daemon=True).start()
    _limit_memory(memory_limit)
    try:
        planner_class = spec.load(quiet=quiet)
    except BaseException as exc:  # import errors, syntax errors, SystemExit at import...
        pipe.send(msgpack.packb([LOAD_ERROR, str(exc)]))
        return
    served = PlannerRuntime(planner_class, host_id, label=spec.describe())
    runtime.append(served)
    pipe.send(msgpack.packb([LOADED, served.plugin_type.value]))
    handle, send, recv = served.handle, pipe.send, pipe.recv  # bound once: the hot loop
    while True:
        try:
            message = recv()
        except (EOFError, OSError):
            break
        if not message:
            break
        op, _, payload = message.partition(b"\0")
        name = op.decode()
        send(handle_batch(served, payload) if name == BATCH_OP else handle(payload, name))
    served.close()
