"""planner-host's recording options, and starting the recorder they ask for."""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Any

import zenoh

from nav2_pyif.common.option_types import positive_int
from nav2_pyif.server.recording.live import LiveTap
from nav2_pyif.server.recording.recorder import Recorder, RecordOptions, key_metadata
from nav2_pyif.server.recording.service import recorded
from nav2_pyif.server.service import PlannerService
from nav2_pyif.server.spec import PlannerSpec

MISSING_MCAP = "--record needs the mcap library: pip install 'nav2-pyif[record]'"


def add_record_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("recording (off by default; replay with nav2-pyif replay)")
    group.add_argument(
        "--record",
        type=Path,
        metavar="FILE.mcap",
        help="record every call (request, reply, their times, the planner's compute time) of "
        "the served keys to this MCAP file, rotated to FILE.1.mcap, FILE.2.mcap, ...",
    )
    group.add_argument(
        "--record-key",
        action="append",
        default=[],
        metavar="PREFIX",
        help="with --record: record only this served key, repeatable (default: every key)",
    )
    group.add_argument(
        "--record-max-size",
        type=positive_int,
        default=100,
        metavar="MB",
        help="with --record: start the next file past this size, >= 1 (default 100)",
    )
    group.add_argument(
        "--record-max-files",
        type=positive_int,
        default=10,
        metavar="N",
        help="with --record: keep the newest N files, removing older ones, >= 1 (default 10)",
    )
    group.add_argument(
        "--allow-live-record",
        action="store_true",
        help="let nav2-pyif record stream a copy of each call of a key over Zenoh to an MCAP "
        "file on its own machine, while it renews its lease (refused otherwise; the router's "
        "access control decides who may ask: docs/record-replay.md)",
    )


def check_record_arguments(
    args: argparse.Namespace, parser: argparse.ArgumentParser, keys: list[str]
) -> None:
    """Exit 2 naming the option that cannot work, before any planner loads."""
    if args.record is None:
        if args.record_key:
            parser.error("--record-key needs --record FILE.mcap")
        return
    directory = args.record.parent
    if not directory.is_dir() or not os.access(directory, os.W_OK):
        parser.error(f"--record {args.record}: its directory is missing or not writable")
    for key in args.record_key:
        if key not in keys:
            parser.error(f"--record-key {key}: not a served key (served: {', '.join(keys)})")
    try:
        import mcap.writer  # noqa: F401
    except ImportError:
        parser.error(MISSING_MCAP)


def _metadata(
    specs: list[PlannerSpec], services: list[PlannerService], wanted: set[str]
) -> dict[str, dict[str, str]]:
    return {
        spec.key: key_metadata(service.plugin_type.value, spec)
        for spec, service in zip(specs, services, strict=True)
        if spec.key in wanted
    }


def start_recording(
    args: argparse.Namespace, specs: list[PlannerSpec], services: list[PlannerService]
) -> tuple[list[Any], Recorder | None]:
    """The services to serve (the recorded ones wrapped) and the recorder, if --record."""
    if args.record is None:
        return list(services), None
    wanted = set(args.record_key) or {spec.key for spec in specs}
    options = RecordOptions(args.record, args.record_max_size * 2**20, args.record_max_files)
    recorder = Recorder(options, _metadata(specs, services, wanted))
    return recorded(services, [spec.key for spec in specs], recorder), recorder


def start_live_tap(
    args: argparse.Namespace,
    session: zenoh.Session,
    specs: list[PlannerSpec],
    services: list[PlannerService],
) -> tuple[list[Any], LiveTap | None]:
    """The services to serve (each key's tapped) and the tap, if --allow-live-record."""
    if not args.allow_live_record:
        return list(services), None
    tap = LiveTap(session, _metadata(specs, services, {spec.key for spec in specs}))
    return recorded(services, [spec.key for spec in specs], tap), tap
