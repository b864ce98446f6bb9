"""Nav2 MPPI's Savitzky-Golay smoothing of the optimal control sequence (utils.hpp
savitskyGolayFilter), in JAX: a 9-point quadratic filter whose window reaches back into the
last four commands sent (the history) and forward past the end by repeating the last
control; the last control itself is left as it is. Sequences under 21 steps are not
smoothed, as in Nav2."""

from __future__ import annotations

from typing import Any

import jax
import jax.numpy as jnp
import numpy as np

#: quadratic, 9 points: the Savitzky-Golay coefficients Nav2 uses
COEFFICIENTS = np.array([-21.0, 14.0, 39.0, 54.0, 59.0, 54.0, 39.0, 14.0, -21.0]) / 231.0


def smooth(sequence: Any, history: Any) -> Any:
    """``sequence`` (T,) and the 4 commands before it, oldest first -> the smoothed (T,)."""
    steps = sequence.shape[0]
    if steps - 1 < 20:
        return sequence
    padded = jnp.concatenate([history, sequence, jnp.repeat(sequence[-1:], 4)])
    # window i covers padded[i : i + 9]: the control i and four either side
    windows = jnp.stack([padded[k : k + steps - 1] for k in range(9)])
    weights = jnp.asarray(COEFFICIENTS, jnp.float32)
    smoothed = jnp.tensordot(weights, windows, axes=1, precision=jax.lax.Precision.HIGHEST)
    return jnp.concatenate([smoothed, sequence[-1:]])
