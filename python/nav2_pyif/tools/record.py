"""``nav2-pyif record``: record the calls of live keys to MCAP files on this machine.

Asks the host serving each key (``P/admin/record``, PROTOCOL.md section 1) to stream a copy
of each call to this tool, renews the stream's lease every second, and writes what comes
with the recorder ``planner-host --record`` uses (server.recording): the same files, replayed
the same way. The host streams only with ``--allow-live-record``, and only while the lease is
renewed: a recorder killed stops the stream within the lease.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import queue
import secrets
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import msgpack
import zenoh
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.common.option_types import positive_float, positive_int
from nav2_pyif.common.zenoh_config import add_zenoh_arguments

#: the lease asked for; renewed every RENEW_S, so a killed recorder's stream ends within it
LEASE_S = 3.0
RENEW_S = 1.0

EXAMPLES = """examples:
  # record a robot's controller and planner until Ctrl-C (its host: --allow-live-record)
  nav2-pyif record --key nav2_pyif/robot1/FollowPath --key nav2_pyif/robot1/GridBased \\
      -o run.mcap

  # one minute, rotated to files of 10 MB, the newest 5 kept
  nav2-pyif record --key nav2_pyif/robot1/FollowPath -o run.mcap --duration 60 \\
      --max-size 10 --max-files 5

  # then replay it as a --record file is replayed
  nav2-pyif replay run.mcap --planner my_pkg.ctrl:MyController
"""


class Refused(RuntimeError):
    """A host refused (or nothing answered) a start."""


def add_record_parser(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = subparsers.add_parser(
        "record",
        help="record the calls of live keys to MCAP files here (replay: nav2-pyif replay)",
        description="Ask the planner host serving each KEY to stream a copy of each call "
        "(request, reply, their times, the planner's compute time) to this tool, and write "
        "them to MCAP files as planner-host --record does. The host must run with "
        "--allow-live-record. Ends on Ctrl-C, SIGTERM or --duration, with a complete file. "
        "Exit code 0 when it recorded, 1 when a host refused or none answered.",
        epilog=EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--key",
        action="append",
        required=True,
        metavar="PREFIX",
        help="a served key prefix to record, repeatable",
    )
    p.add_argument(
        "-o", "--output", type=Path, required=True, metavar="FILE.mcap", help="the first file"
    )
    p.add_argument(
        "--duration", type=positive_float, metavar="SECONDS", help="stop after this long, > 0"
    )
    p.add_argument(
        "--max-size",
        type=positive_int,
        default=100,
        metavar="MB",
        help="start the next file (FILE.1.mcap, ...) past this size, >= 1 (default 100)",
    )
    p.add_argument(
        "--max-files",
        type=positive_int,
        default=10,
        metavar="N",
        help="keep the newest N files, removing older ones, >= 1 (default 10)",
    )
    p.add_argument(
        "--timeout",
        type=positive_float,
        default=10.0,
        metavar="SECONDS",
        help="how long to wait for a router and each key's host, > 0 (default 10)",
    )
    add_zenoh_arguments(p, default_mode="client")
    p.set_defaults(func=run_record, parser=p)


def run_record(args: argparse.Namespace) -> int:
    from nav2_pyif.common.reach import open_tool_session
    from nav2_pyif.common.zenoh_config import options_from_args
    from nav2_pyif.tools.admin import NoPlannerHost

    parser: argparse.ArgumentParser = args.parser
    directory = args.output.parent
    if not directory.is_dir() or not os.access(directory, os.W_OK):
        parser.error(f"--output {args.output}: its directory is missing or not writable")
    for key in args.key:
        try:
            KeySpace(key)
        except ValueError as exc:
            parser.error(f"--key {key}: {exc}")
    try:
        import mcap.writer  # noqa: F401
    except ImportError:
        parser.error("needs the mcap library: pip install 'nav2-pyif[record]'")
    try:
        session = open_tool_session(options_from_args(args), "nav2-pyif record", args.timeout)
    except (ConnectionError, FileNotFoundError) as exc:
        print(f"nav2-pyif record: {exc}", file=sys.stderr)
        return 1
    try:
        return LiveRecording(session, args).run()
    except (Refused, NoPlannerHost) as exc:
        print(f"nav2-pyif record: {exc}", file=sys.stderr)
        return 1
    finally:
        session.close()


class LiveRecording:
    def __init__(self, session: zenoh.Session, args: argparse.Namespace) -> None:
        self.session, self.args = session, args
        self.stream_id = secrets.token_hex(4)
        self.arrived: queue.SimpleQueue[tuple[str, bytes]] = queue.SimpleQueue()
        self.started: list[str] = []

    def _arrival(self, key: str) -> Callable[[Any], None]:
        """On Zenoh's thread: only queue what came (writing happens on this tool's)."""

        def arrived(sample: Any) -> None:
            self.arrived.put((key, sample.payload.to_bytes()))

        return arrived

    def _ask(self, key: str, action: str, timeout: float) -> dict[str, Any] | None:
        request = {"action": action, "stream": self.stream_id, "lease_s": LEASE_S}
        for reply in self.session.get(
            KeySpace(key).admin_record, payload=msgpack.packb(request), timeout=timeout
        ):
            if reply.ok is not None:
                answer: dict[str, Any] = msgpack.unpackb(reply.ok.payload.to_bytes())
                return answer
        return None

    def run(self) -> int:
        from nav2_pyif.server.recording.recorder import Recorder, RecordOptions
        from nav2_pyif.tools.admin import wait_for_host

        args = self.args
        subscribers = []
        try:
            metadata: dict[str, dict[str, str]] = {}
            restores: dict[str, list[bytes]] = {}
            for key in args.key:
                wait_for_host(self.session, KeySpace(key), args.timeout)
                subscribers.append(
                    self.session.declare_subscriber(
                        KeySpace(key).record_stream(self.stream_id),
                        self._arrival(key),
                    )
                )
                answer = self._ask(key, "start", args.timeout)
                if answer is None:
                    raise Refused(
                        f"nothing answered a record request on {KeySpace(key).admin_record} "
                        "(a router's access control that does not let this identity record, "
                        "or a planner-host too old to stream)"
                    )
                if not answer.get("ok"):
                    raise Refused(f"{key}: {answer.get('message')}")
                self.started.append(key)
                metadata[key] = dict(answer.get("metadata") or {})
                restores[key] = list(answer.get("restore") or [])
            options = RecordOptions(
                args.output, args.max_size * 2**20, args.max_files, after_reply_ns=0
            )
            recorder = Recorder(options, metadata)
            try:
                for key, requests in restores.items():
                    recorder.restore(key, requests)
                self._record(recorder)
            finally:
                self._stop()
                self._drain(recorder)
                recorder.close()
                print(
                    f"nav2-pyif record: {recorder.written} call(s) of {', '.join(args.key)} in "
                    f"{', '.join(str(p) for p in recorder.paths)}",
                    file=sys.stderr,
                )
        finally:
            self._stop()
            for subscriber in subscribers:
                subscriber.undeclare()
        return 0

    def _record(self, recorder: Any) -> None:
        """Until --duration (or a signal, raised here): write what arrives, renew the lease."""
        began = time.monotonic()
        end = began + self.args.duration if self.args.duration else float("inf")
        renew = began + RENEW_S
        while (now := time.monotonic()) < end:
            self._drain(recorder, min(end, renew) - now)
            if time.monotonic() >= renew:
                renew += RENEW_S
                for key in self.started:
                    answer = self._ask(key, "renew", RENEW_S)
                    if answer is not None and not answer.get("ok"):
                        # the host lost the stream (restarted, or our lease lapsed): start again
                        again = self._ask(key, "start", RENEW_S) or {}
                        if again.get("ok"):
                            recorder.restore(key, list(again.get("restore") or []))

    def _drain(self, recorder: Any, wait: float = 0.0) -> None:
        try:
            item = self.arrived.get(timeout=wait) if wait > 0 else self.arrived.get_nowait()
        except queue.Empty:
            return
        while True:
            key, data = item
            op, request, reply, t0, t1 = msgpack.unpackb(data)
            if op is None:
                recorder.reloaded(key, request.decode())
            else:
                recorder.add(key, op, request, reply, t0, t1)
            try:
                item = self.arrived.get_nowait()
            except queue.Empty:
                return

    def _stop(self) -> None:
        """Ask each host to stop streaming (best effort: the lease ends it anyway)."""
        while self.started:
            key = self.started.pop()
            with contextlib.suppress(Exception):
                self._ask(key, "stop", 1.0)
