"""The learned controller's features: a batch's scans pooled together give each robot exactly
what its scan alone gives, and that is the nearest return per sector."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from nav2_pyif_planners.learned.features import (
    SCAN_CLIP,
    SECTORS,
    features,
    features_of,
    plan_window,
    scan_sectors,
    scan_sectors_of,
)

pytestmark = pytest.mark.unit


def nearest_per_sector(ranges: np.ndarray, angles: np.ndarray) -> list[float]:
    """The definition, beam by beam: the nearest finite return in each sector, clipped (the
    beam's sector in the scan's own float32 arithmetic, as a boundary beam falls there)."""
    out = [SCAN_CLIP] * SECTORS
    for r, a in zip(ranges.tolist(), angles, strict=True):
        turned = np.mod(a + math.pi, 2 * math.pi) / (2 * math.pi) * SECTORS
        sector = min(max(int(turned), 0), SECTORS - 1)
        value = min(max(r, 0.0), SCAN_CLIP) if math.isfinite(r) else SCAN_CLIP
        out[sector] = min(out[sector], value)
    return out


def a_scan(rng: np.random.Generator, beams: int, start: float, step: float) -> tuple[Any, Any]:
    angles = (start + step * np.arange(beams)).astype(np.float32)
    ranges = rng.uniform(-0.5, 5.0, beams).astype(np.float32)
    ranges[rng.random(beams) < 0.1] = np.inf
    ranges[rng.random(beams) < 0.05] = np.nan
    return ranges, angles


def test_pooled_scans_of_two_sensor_models_give_each_robot_its_own_nearest_returns() -> None:
    rng = np.random.default_rng(7)
    models = [(360, -math.pi, 2 * math.pi / 360), (90, -0.8, 0.02), (0, 0.0, 0.1)]
    scans = [a_scan(rng, *models[i % len(models)]) for i in range(9)]
    pooled = scan_sectors_of(scans)
    assert pooled.shape == (9, SECTORS)
    for row, (ranges, angles) in zip(pooled, scans, strict=True):
        assert row.tolist() == pytest.approx(nearest_per_sector(ranges, angles), abs=1e-6)
        assert np.array_equal(row, scan_sectors(ranges, angles))


def test_a_batch_of_features_is_each_robots_features_stacked() -> None:
    rng = np.random.default_rng(3)
    rows, scans, windows, velocities = [], [], [], []
    for i in range(5):
        ranges, angles = a_scan(rng, 360, -math.pi, 2 * math.pi / 360)
        path = np.cumsum(rng.uniform(0.0, 0.1, (40, 2)), axis=0)
        pose, velocity = (0.1 * i, 0.2, 0.3 * i), (0.4, -0.1 * i)
        rows.append(features(ranges, angles, path, i, pose, velocity))
        scans.append((ranges, angles))
        windows.append(plan_window(path, i, *pose))
        velocities.append(velocity)
    batch = features_of(scans, np.stack(windows), np.array(velocities))
    assert batch.dtype == np.float32
    assert np.array_equal(batch, np.stack(rows))
