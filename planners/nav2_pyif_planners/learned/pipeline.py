"""``nav2-pyif learn``: demonstrations from the reference MPPI in the offline runner on the
bundled maps (with the simulated laser as input "scan"), a policy trained on them, its
weights saved, and a drive with the learned controller on the office map."""

from __future__ import annotations

import logging
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from nav2_pyif.params import ParamValue
from nav2_pyif.runner.laser import LaserSpec
from nav2_pyif.runner.maps import map_path
from nav2_pyif.runner.run import Pose3, SimConfig, SimResult, run_sim
from nav2_pyif.runner.sensing import SensingConfig

from nav2_pyif_planners.learned.policy import Training, default_weights, train

log = logging.getLogger("nav2_pyif.learn")
RECORDER = "nav2_pyif_planners.learned.record:RecordingMPPI"
LEARNED = "nav2_pyif_planners.learned.controller:LearnedController"


@dataclass(frozen=True)
class Task:
    map: str
    start: Pose3 | None = None  # None: the map's own task
    goal: Pose3 | None = None


@dataclass
class LearnConfig:
    tasks: list[Task] = field(default_factory=lambda: [Task("office"), Task("cluttered")])
    runs: int = 2  # demonstrations per task: one clean, the others with executed noise
    steps: int = 3000  # training steps
    weights: Path = field(default_factory=default_weights)
    evaluate: Task | None = field(default_factory=lambda: Task("office"))  # None: no drive
    mppi: dict[str, ParamValue] = field(default_factory=dict)  # the expert's parameters
    action_noise: float = 0.1
    timeout: float = 180.0  # [s] simulated, per run
    laser: LaserSpec = field(default_factory=LaserSpec)
    progress: bool = False  # progress bars on stderr


@dataclass
class LearnResult:
    demonstrations: list[SimResult]
    training: Training
    weights: Path
    drive: SimResult | None


def sim_config(
    config: LearnConfig, task: Task, controller: str, params: dict[str, ParamValue]
) -> SimConfig:
    """A runner run of ``controller`` on ``task`` with the simulated laser as input "scan"."""
    return SimConfig(
        map=map_path(task.map),
        controller=controller,
        start=task.start,
        goal=task.goal,
        timeout=config.timeout,
        controller_params=params,
        sensing=SensingConfig(config.laser, debug_every=0.0),
        call_timeout=5.0,  # simulated time waits for the planner: a busy machine is no failure
        progress=config.progress,
    )


def collect(config: LearnConfig, directory: Path) -> tuple[np.ndarray, np.ndarray, list[SimResult]]:
    """(features (N, F), commands (N, 2)) of every demonstration, and the runs."""
    xs: list[np.ndarray] = []
    ys: list[np.ndarray] = []
    runs: list[SimResult] = []
    total = len(config.tasks) * config.runs
    for t, task in enumerate(config.tasks):
        for run in range(config.runs):
            record = directory / f"demo_{t}_{run}.npz"
            params: dict[str, ParamValue] = {
                **config.mppi,
                "record_to": str(record),
                "seed": 100 * t + run,
                "action_noise": config.action_noise if run else 0.0,  # one clean run each
            }
            log.info("demonstration %d/%d: MPPI on %s", len(runs) + 1, total, task.map)
            result = run_sim(sim_config(config, task, RECORDER, params))
            runs.append(result)
            samples = 0
            if result.reached and record.is_file():  # a failed run teaches how to fail
                with np.load(record) as data:
                    xs.append(data["x"])
                    ys.append(data["y"])
                    samples = len(data["x"])
            log.info(
                "  %s in %.1f s: %s",
                result.outcome,
                result.sim_time,
                f"{samples} samples" if samples else "left out",
            )
    if not xs:
        raise RuntimeError("no demonstration reached its goal: nothing to learn from")
    return np.concatenate(xs), np.concatenate(ys), runs


def learn(config: LearnConfig) -> LearnResult:
    with tempfile.TemporaryDirectory(prefix="nav2_pyif_demos_") as tmp:
        x, y, runs = collect(config, Path(tmp))
    log.info("training on %d samples, %d steps", len(x), config.steps)
    policy, training = train(x, y, steps=config.steps, progress=config.progress)
    policy.save(config.weights)
    log.info(
        "trained in %.1f s on %s (loss %.4f); weights in %s",
        training.seconds,
        training.device,
        training.loss,
        config.weights,
    )
    drive = None
    if config.evaluate is not None:
        log.info("driving %s with the learned controller", config.evaluate.map)
        params: dict[str, ParamValue] = {"weights": str(config.weights)}
        drive = run_sim(sim_config(config, config.evaluate, LEARNED, params))
    return LearnResult(runs, training, config.weights, drive)
