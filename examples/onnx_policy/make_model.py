"""Write the policy as an ONNX file: a 3-32-2 tanh network fitted with NumPy alone.

The hidden layer is random and fixed; the output layer is the least-squares fit of the teacher
(features.py) over sampled situations (an "extreme learning machine": no training framework).
The graph is built with ``onnx.helper`` from those NumPy weights and checked with onnx.checker.

    python examples/onnx_policy/make_model.py out/policy.onnx
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script from anywhere
from onnx_policy.features import features, teacher

HIDDEN = 32


def fit(seed: int = 0, samples: int = 20000) -> list[np.ndarray]:
    """The four weight arrays W1 (3, H), b1 (H,), W2 (H, 2), b2 (2,), float32."""
    rng = np.random.default_rng(seed)
    e, d = rng.uniform(-np.pi, np.pi, samples), rng.uniform(0.0, 1.5, samples)
    x, y = features(e, d).astype(np.float64), teacher(e, d)
    w1, b1 = rng.normal(0, 1.5, (3, HIDDEN)), rng.normal(0, 1.0, HIDDEN)
    h = np.column_stack([np.tanh(x @ w1 + b1), np.ones(samples)])
    out = np.linalg.solve(h.T @ h + 1e-4 * np.eye(HIDDEN + 1), h.T @ y)  # ridge least squares
    return [a.astype(np.float32) for a in (w1, b1, out[:-1], out[-1])]


def model(weights: list[np.ndarray]) -> onnx.ModelProto:
    """features (N, 3) -> Gemm -> Tanh -> Gemm -> command (N, 2) v [m/s], w [rad/s]."""
    names = ["w1", "b1", "w2", "b2"]
    graph = helper.make_graph(
        [
            helper.make_node("Gemm", ["features", "w1", "b1"], ["hidden"]),
            helper.make_node("Tanh", ["hidden"], ["activation"]),
            helper.make_node("Gemm", ["activation", "w2", "b2"], ["command"]),
        ],
        "policy",
        [helper.make_tensor_value_info("features", TensorProto.FLOAT, ["N", 3])],
        [helper.make_tensor_value_info("command", TensorProto.FLOAT, ["N", 2])],
        [numpy_helper.from_array(a, n) for a, n in zip(weights, names, strict=True)],
    )
    made = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    made.ir_version = 8  # readable by onnxruntime releases of the last three years
    onnx.checker.check_model(made)
    return made


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", type=Path, help="the .onnx file to write")
    parser.add_argument("--seed", type=int, default=0, help="of the random hidden layer")
    args = parser.parse_args()
    weights = fit(args.seed)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    onnx.save(model(weights), args.output)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
