"""Costmap look-ups inside the compiled step: one fused gather per batch of points from the
flat uint8 grid, and Nav2's footprint cost (the most costly cell under the footprint's edges,
LETHAL once a corner leaves the map, as FootprintCollisionChecker::footprintCost)."""

from __future__ import annotations

from typing import Any, NamedTuple

import jax.numpy as jnp

LETHAL = 254.0
INSCRIBED = 253.0
NO_INFORMATION = 255.0


class Grid(NamedTuple):
    """The costmap on the device: ``data`` (H, W) uint8 (Nav2's layout, cell (mx, my) at
    ``data[my, mx]``); ``meta`` (origin_x, origin_y, resolution) float32;
    ``outline`` (M, 2) points on the footprint's edges [m], robot frame; ``robot`` (possible
    collision cost, inscribed radius, inflation radius, cost scaling factor) float32, Nav2's
    names: the cost above which the footprint must be checked, and the inflation layer's."""

    data: Any
    meta: Any
    outline: Any
    robot: Any


def cell(grid: Grid, x: Any, y: Any) -> tuple[Any, Any]:
    """World points -> (flat cell index, inside the map). Off-map indices are clipped: read
    with ``inside``."""
    height, width = grid.data.shape
    mx = jnp.floor((x - grid.meta[0]) / grid.meta[2])
    my = jnp.floor((y - grid.meta[1]) / grid.meta[2])
    inside = (mx >= 0) & (my >= 0) & (mx < width) & (my < height)
    mx = jnp.clip(mx, 0, width - 1).astype(jnp.int32)
    my = jnp.clip(my, 0, height - 1).astype(jnp.int32)
    return my * width + mx, inside


def point_cost(grid: Grid, x: Any, y: Any) -> Any:
    """Cost (float32) under each point; NO_INFORMATION off the map, as the critics do."""
    index, inside = cell(grid, x, y)
    cost = jnp.take(grid.data.ravel(), index, mode="clip").astype(jnp.float32)
    return jnp.where(inside, cost, NO_INFORMATION)


def footprint_cost(grid: Grid, x: Any, y: Any, cos: Any, sin: Any) -> Any:
    """Nav2's footprintCostAtPose at each pose (any shape; its heading's ``cos`` and
    ``sin``, as the roll-out computed them): the most costly cell under the footprint's
    outline; LETHAL when any outline point is off the map."""
    c, s = cos[..., None], sin[..., None]
    ox, oy = grid.outline[:, 0], grid.outline[:, 1]
    wx = x[..., None] + c * ox - s * oy
    wy = y[..., None] + s * ox + c * oy
    index, inside = cell(grid, wx, wy)
    cost = jnp.take(grid.data.ravel(), index, mode="clip").max(axis=-1).astype(jnp.float32)
    return jnp.where(inside.all(axis=-1), cost, LETHAL)
