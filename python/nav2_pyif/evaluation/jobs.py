"""One run of ``nav2-pyif eval`` (a planner pair on a scenario), and many in parallel
processes, each run with a planner host of its own, with a progress bar.

Lockstep by default (the runner's, SimConfig.realtime False): simulated time advances one
control period per cycle only once the planner has answered, so what the robot does does not
depend on how loaded the machine is. With ``realtime`` the loop keeps wall-clock pace and
each reply must come within the plugin's call timeout, as on a robot.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import logging
import multiprocessing
import os
import signal
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from nav2_pyif.common.signals import Interrupted, raise_on_signals
from nav2_pyif.evaluation.metrics import run_metrics
from nav2_pyif.evaluation.scenarios import Scenario

#: Lockstep: how long a host may take to start, and a plan to come [s]. Generous, so that a
#: loaded machine only slows an evaluation down and changes none of its verdicts.
LOAD_WAIT = 300.0
#: A row's driven path (x, y), which the scenario's picture takes and the report leaves out.
PATH_KEY = "_path"


@dataclass(frozen=True)
class Entrant:
    """What one column of the report runs: a controller and a global planner (sim's specs)."""

    controller: str
    planner: str
    label: str


@dataclass(frozen=True)
class Settings:
    rate: float = 20.0
    timeout: float = 120.0  # [s] simulated
    realtime: bool = False
    path: tuple[str, ...] = ()
    draw_to: Path | None = None  # a PNG per run under it, by scenario
    barn_max_speed: float = 2.0


@dataclass(frozen=True)
class Job:
    scenario: Scenario
    entrant: Entrant
    settings: Settings = field(default_factory=Settings)


def run_job(job: Job) -> dict[str, Any]:
    """Run ``job`` (in this process, with a planner host of its own): its report row."""
    from nav2_pyif.exceptions import Nav2Error
    from nav2_pyif.runner.run import SimConfig, SimError, run_sim

    s = job.settings
    config = SimConfig(
        map=job.scenario.map,
        controller=job.entrant.controller,
        planner=job.entrant.planner,
        start=job.scenario.start,
        goal=job.scenario.goal,
        rate=s.rate,
        timeout=s.timeout,
        realtime=s.realtime,
        path=list(s.path),
        # waits for the machine, not verdicts: a loaded machine starts hosts slowly
        startup_wait=LOAD_WAIT if not s.realtime else SimConfig.startup_wait,
        plan_wait=LOAD_WAIT if not s.realtime else SimConfig.plan_wait,
    )
    row: dict[str, Any] = {"scenario": job.scenario.name, "planner": job.entrant.label}
    try:
        result = run_sim(config)
    except (SimError, RuntimeError, TimeoutError, ConnectionError, Nav2Error) as exc:
        return {**row, "success": False, "outcome": f"error: {exc}"}
    row.update(run_metrics(result, job.scenario.optimal_length, s.barn_max_speed))
    # the driven path, for the scenario's picture (taken out of the row before the report)
    row[PATH_KEY] = [(round(t[1], 3), round(t[2], 3)) for t in result.trajectory]
    if s.draw_to is not None:
        from nav2_pyif.runner.plot import draw

        folder = s.draw_to / job.scenario.name
        folder.mkdir(parents=True, exist_ok=True)
        stem = folder / job.entrant.label.replace(":", ".")
        draw(result, stem.with_suffix(".png"))
        if result.host_log:  # the host's own account of a planner that crashed or hung
            stem.with_suffix(".host.log").write_text(result.host_log)
    return row


def _run_in_worker(job: Job) -> dict[str, Any]:
    """``run_job`` in a pool process. Stopped by the parent (SIGTERM), the run has stopped its
    host on the way out; the process then ends at once rather than take the next job."""
    try:
        return run_job(job)
    except Interrupted as exc:
        os._exit(exc.exit_code)


def _worker_start() -> None:
    """A pool process: quiet (the bar is the parent's), and a SIGTERM from the parent stops
    its run and that run's planner host (Interrupted through run_sim's clean-up)."""
    logging.getLogger("nav2_pyif").setLevel(logging.WARNING)
    raise_on_signals()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C is the parent's to pass on


def run_jobs(
    jobs: list[Job], workers: int, on_done: Callable[[dict[str, Any]], None]
) -> list[dict[str, Any]]:
    """Every job's row, in ``jobs``' order, run in ``workers`` processes (1: here)."""
    if workers == 1:
        done = []
        for job in jobs:
            done.append(run_job(job))
            on_done(done[-1])
        return done
    # spawn: a fork would copy this process's Zenoh runtime threads, which do not survive it
    context = multiprocessing.get_context("spawn")
    pool = concurrent.futures.ProcessPoolExecutor(
        max_workers=workers, mp_context=context, initializer=_worker_start
    )
    try:
        futures = {pool.submit(_run_in_worker, job): i for i, job in enumerate(jobs)}
        rows: list[dict[str, Any] | None] = [None] * len(jobs)
        for future in concurrent.futures.as_completed(futures):
            rows[futures[future]] = future.result()
            on_done(future.result())
        return [r for r in rows if r is not None]
    except Interrupted:
        _stop_workers(pool)
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _stop_workers(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """SIGTERM to each of the pool's processes (only ours): each stops its run and host."""
    for pid in list(_pool_pids(pool)):
        with contextlib.suppress(ProcessLookupError):  # ended already
            os.kill(pid, signal.SIGTERM)


def _pool_pids(pool: concurrent.futures.ProcessPoolExecutor) -> Iterator[int]:
    processes: dict[int, Any] = getattr(pool, "_processes", None) or {}
    yield from processes
