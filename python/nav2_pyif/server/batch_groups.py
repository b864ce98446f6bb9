"""``planner-host --batch``: which keys share a batched planner, and its options.

Keys asking for batching (``--batch``, or ``batch: true`` in a ``--config`` entry) that serve
the same planner form one group: one worker (or one in-process planner), every robot's
session in it, their control cycles batched (batch_gate). A group whose planner is not a
controller has nothing to batch: its keys keep a planner each, as without ``--batch``.
"""

from __future__ import annotations

import argparse
import logging
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

from nav2_pyif_protocol.constants import PluginType

from nav2_pyif.common.option_types import non_negative_float, positive_float
from nav2_pyif.exceptions import PlannerLoadError
from nav2_pyif.server.batch_gate import BatchGroup, check_window
from nav2_pyif.server.service import PlannerService
from nav2_pyif.server.spec import PlannerSpec

log = logging.getLogger("nav2_pyif.server.host")
Start = Callable[[PlannerSpec], PlannerService]


def add_batch_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("one planner for a fleet (batched control cycles)")
    group.add_argument(
        "--batch",
        action="store_true",
        help="controller keys served by the same planner share one worker, and their "
        "compute_velocity_commands calls arriving within --batch-window become one call of "
        "the planner's compute_velocity_commands_batch (robot by robot where it has none)",
    )
    group.add_argument(
        "--batch-window",
        type=non_negative_float,
        default=5.0,
        metavar="MS",
        help="the longest a control cycle waits for others to join its batch, in ms, at "
        "most 1/4 of --control-period; a batch leaves as soon as every robot that called in "
        "the last two periods is in it (default 5)",
    )
    group.add_argument(
        "--control-period",
        type=positive_float,
        default=0.05,
        metavar="SECONDS",
        help="the robots' control period (1 / controller_frequency), which bounds "
        "--batch-window (default 0.05: 20 Hz)",
    )


def check_batch_arguments(args: argparse.Namespace, parser: argparse.ArgumentParser) -> None:
    try:
        check_window(args.batch_window / 1000.0, args.control_period)
    except ValueError as exc:
        parser.error(f"--batch-window: {exc}")


def group_key(spec: PlannerSpec) -> str:
    """The name a group's shared planner goes by in the log: ``batch:<planner>``."""
    return f"batch:{spec.describe()}"


def start_all(
    specs: list[PlannerSpec], host_id: str, args: argparse.Namespace, start: Start
) -> list[PlannerService]:
    """A service per spec, in order: the keys of a batch group get members of one shared
    planner. Planners load in parallel; if one cannot load, the others are stopped and its
    PlannerLoadError is raised."""
    groups: dict[tuple[object, ...], list[int]] = {}
    alone: list[int] = []
    for i, spec in enumerate(specs):
        if spec.batch or args.batch:
            what = (spec.planner, spec.module, tuple(sorted(spec.delegates.items())), spec.kind)
            groups.setdefault(what, []).append(i)
        else:
            alone.append(i)
    heads = [
        PlannerSpec(group_key(specs[m[0]]), specs[m[0]].planner, specs[m[0]].module,
                    dict(specs[m[0]].delegates), specs[m[0]].kind, batch=True)
        for m in groups.values()
    ]  # fmt: skip
    services: list[PlannerService | None] = [None] * len(specs)
    started: list[PlannerService] = []  # what to close if one cannot load
    error: PlannerLoadError | None = None
    with ThreadPoolExecutor(max_workers=max(1, min(8, len(alone) + len(heads)))) as pool:
        singles = [(i, pool.submit(start, specs[i])) for i in alone]
        shared = [
            (members, pool.submit(start, head))
            for members, head in zip(groups.values(), heads, strict=True)
        ]
    for i, future in singles:
        try:
            services[i] = future.result()
            started.append(services[i])  # type: ignore[arg-type]
        except PlannerLoadError as exc:
            error = error or exc
    for members, future in shared:
        try:
            service = future.result()
        except PlannerLoadError as exc:
            error = error or exc
            continue
        started.append(service)
        if service.plugin_type is not PluginType.CONTROLLER:
            log.info(
                "--batch: %s is a %s: only controllers' cycles are batched; its %d key(s) "
                "keep a planner each",
                service.label,
                service.plugin_type.value,
                len(members),
            )
            service.close()
            started.remove(service)
            for i in members:
                try:
                    services[i] = start(specs[i])
                    started.append(services[i])  # type: ignore[arg-type]
                except PlannerLoadError as exc:
                    error = error or exc
            continue
        group = BatchGroup(service, host_id, args.batch_window / 1000.0, args.control_period)
        started.remove(service)
        for i in members:
            services[i] = group.member(specs[i].key)
            started.append(services[i])  # type: ignore[arg-type]  # the last closes the group
        log.info(
            "batch group: %s serves %d key(s) from %s, window %g ms (control period %g s)",
            service.label,
            len(members),
            service.where,
            args.batch_window,
            args.control_period,
        )
    if error is not None:
        for service in started:
            service.close()
        raise error
    return [service for service in services if service is not None]
