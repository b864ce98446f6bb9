"""The policy: a small MLP, features -> (v, w), trained by regression on demonstrations with
JAX (Adam written out: three lines, no optimiser library). Weights are plain NumPy arrays in
an .npz, with the input normalisation, so serving needs nothing but this file."""

from __future__ import annotations

import itertools
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

HIDDEN = (128, 128)


def import_jax() -> Any:
    """JAX, or an ImportError that says how to install it."""
    try:
        import jax
    except ImportError as exc:
        import sys

        raise ImportError(
            f"the learned controller needs JAX, which {sys.executable} lacks: "
            f"{sys.executable} -m pip install 'jax>=0.4.30' (CPU; 'jax[cuda12]' for NVIDIA "
            "GPUs); in a checkout, NAV2_PYIF_EXTRAS=dev,jax ./scripts/bootstrap.sh"
        ) from exc
    return jax


def default_weights() -> Path:
    """Where ``nav2-pyif learn`` keeps weights: the user's data directory."""
    base = os.environ.get("XDG_DATA_HOME") or Path.home() / ".local" / "share"
    return Path(base) / "nav2_pyif" / "learned" / "policy.npz"


@dataclass
class Policy:
    layers: list[tuple[np.ndarray, np.ndarray]]  # (W, b) per layer
    mean: np.ndarray  # feature normalisation
    std: np.ndarray
    scale: np.ndarray  # (2,) output scale: v [m/s], w [rad/s]

    def save(self, path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        arrays: dict[str, Any] = {"mean": self.mean, "std": self.std, "scale": self.scale}
        arrays |= {f"w{i}": w for i, (w, _) in enumerate(self.layers)}
        arrays |= {f"b{i}": b for i, (_, b) in enumerate(self.layers)}
        np.savez(path, **arrays)

    @classmethod
    def load(cls, path: Path) -> Policy:
        with np.load(path) as data:
            count = sum(1 for k in data.files if k.startswith("w"))
            layers = [(data[f"w{i}"], data[f"b{i}"]) for i in range(count)]
            return cls(layers, data["mean"], data["std"], data["scale"])


def forward(params: Any, x: Any) -> Any:
    """(B, F) normalised features -> (B, 2) in [-1, 1] (times ``scale``: v, w)."""
    import jax.numpy as jnp

    for w, b in params[:-1]:
        x = jnp.tanh(x @ w + b)
    w, b = params[-1]
    return jnp.tanh(x @ w + b)


@dataclass(frozen=True)
class Training:
    steps: int
    seconds: float
    loss: float  # mean squared error over all samples, outputs scaled to [-1, 1]
    samples: int
    device: str  # where it trained: JAX's default device


def train(
    x: np.ndarray,
    y: np.ndarray,
    steps: int = 3000,
    seed: int = 0,
    batch: int = 256,
    progress: bool = False,
) -> tuple[Policy, Training]:
    """Fit the MLP to (x (N, F), y (N, 2) v, w) on JAX's default device (a GPU where JAX
    has one); ``progress``: a progress bar on stderr."""
    jax = import_jax()
    import jax.numpy as jnp
    from tqdm import tqdm

    started = time.perf_counter()
    mean, std = x.mean(axis=0), x.std(axis=0) + 1e-3
    scale = np.maximum(np.abs(y).max(axis=0), 1e-3).astype(np.float32)
    xn = jnp.asarray((x - mean) / std, dtype=jnp.float32)
    yn = jnp.asarray(y / scale, dtype=jnp.float32)
    key = jax.random.PRNGKey(seed)
    sizes = (x.shape[1], *HIDDEN, 2)
    params = []
    for fan_in, fan_out in itertools.pairwise(sizes):
        key, sub = jax.random.split(key)
        w = jax.random.normal(sub, (fan_in, fan_out)) * jnp.sqrt(1.0 / fan_in)
        params.append((w, jnp.zeros(fan_out)))

    def loss_fn(p: Any, xb: Any, yb: Any) -> Any:
        return jnp.mean((forward(p, xb) - yb) ** 2)

    def adam_step(state: Any, i: Any, key: Any) -> Any:
        p, m, v = state
        idx = jax.random.randint(key, (batch,), 0, xn.shape[0])
        loss, g = jax.value_and_grad(loss_fn)(p, xn[idx], yn[idx])
        lr = 3e-3 * (0.05 + 0.95 * (1.0 - i / steps))  # linear decay
        m = jax.tree_util.tree_map(lambda a, b: 0.9 * a + 0.1 * b, m, g)
        v = jax.tree_util.tree_map(lambda a, b: 0.999 * a + 0.001 * b * b, v, g)
        t = i + 1.0
        p = jax.tree_util.tree_map(
            lambda w, a, b: w - lr * (a / (1 - 0.9**t)) / (jnp.sqrt(b / (1 - 0.999**t)) + 1e-8),
            p,
            m,
            v,
        )
        return (p, m, v), loss

    step = jax.jit(adam_step)
    zeros = jax.tree_util.tree_map(jnp.zeros_like, params)
    state = (params, zeros, zeros)
    keys = jax.random.split(key, steps)
    with tqdm(total=steps, unit="step", disable=not progress, desc="training") as bar:
        for i in range(steps):
            state, loss = step(state, float(i), keys[i])
            if i % 100 == 99 or i == steps - 1:
                bar.update(i + 1 - bar.n)
                bar.set_postfix_str(f"batch loss {float(loss):.4f}")
    final = float(loss_fn(state[0], xn, yn))
    layers = [(np.asarray(w), np.asarray(b)) for w, b in state[0]]
    policy = Policy(layers, mean.astype(np.float32), std.astype(np.float32), scale)
    device = str(jax.devices()[0])
    return policy, Training(steps, time.perf_counter() - started, final, len(x), device)
