"""Nav2's MPPI controller (nav2_mppi_controller, Jazzy) in JAX, as ``Nav2MPPI``: the same
critics, parameters (Nav2's names and defaults), motion models, acceleration limits,
Savitzky-Golay smoothing and warm start, one jit-compiled step per cycle. See the MPPI guide.

Files, one job each: params.py (Nav2's parameter table), models.py (motion models), costs.py
(costmap look-ups), critics.py, smoothing.py, optimizer.py (the compiled step), path.py (the
plan's pruning), controller.py (the Nav2 controller), fleet.py (a batched host's robots),
lanes.py (the device each robot's step runs on). Needs JAX (nav2-pyif-planners[jax])."""

try:
    import jax  # noqa: F401
except ImportError as exc:  # a clear reason at load time, as mppi_jax gives
    import sys

    raise ImportError(
        f"nav2_pyif_planners.mppi_nav2 needs JAX, which {sys.executable} lacks: "
        f"{sys.executable} -m pip install 'jax>=0.4.30' (CPU; 'jax[cuda12]' for NVIDIA GPUs); "
        "in a checkout, NAV2_PYIF_EXTRAS=dev,jax ./scripts/bootstrap.sh"
    ) from exc

from nav2_pyif_planners.mppi_nav2.lanes import claim_cpu_lanes

claim_cpu_lanes()  # before JAX starts: a fleet's steps one per core (lanes.py)

from nav2_pyif_planners.mppi_nav2.controller import Nav2MPPI  # noqa: E402
from nav2_pyif_planners.mppi_nav2.params import (  # noqa: E402
    NAV2_JAZZY_FILE,
    flatten,
    nav2_jazzy_params,
)

__all__ = ["NAV2_JAZZY_FILE", "Nav2MPPI", "flatten", "nav2_jazzy_params"]
