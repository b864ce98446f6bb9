"""The MPC's optimisation problem in CasADi's Opti stack: a unicycle over N steps of dt.

Decision variables: states X (3, N+1) x, y [m], yaw [rad]; controls U (2, N) v [m/s], w [rad/s].
Parameters, set each cycle: the robot's pose (3,), the reference poses (3, N) along the plan,
and K obstacle points (2, K) [m], kept at ``safe`` metres by a soft penalty.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

OBSTACLES = 8  # the nearest obstacle points the problem keeps clear of


@dataclass(frozen=True)
class Limits:
    max_speed: float  # [m/s]
    max_turn: float  # [rad/s]
    safe: float  # [m] from the robot's centre to an obstacle point, softly


class Problem:
    """Built once (IPOPT's symbolic set-up is the slow part), solved every cycle."""

    def __init__(self, steps: int, dt: float, limits: Limits) -> None:
        self.opti = opti = ca.Opti()
        self.states, self.controls = opti.variable(3, steps + 1), opti.variable(2, steps)
        self.pose, self.ref = opti.parameter(3), opti.parameter(3, steps)
        self.obstacles = opti.parameter(2, OBSTACLES)
        X, U = self.states, self.controls  # noqa: N806 (the usual names)
        opti.subject_to(X[:, 0] == self.pose)
        cost = ca.MX(0)
        for k in range(steps):  # explicit Euler: dt is the control period, a short step
            v, w, yaw = U[0, k], U[1, k], X[2, k]
            opti.subject_to(
                X[:, k + 1] == X[:, k] + dt * ca.vertcat(v * ca.cos(yaw), v * ca.sin(yaw), w)
            )
            error = X[:2, k + 1] - self.ref[:2, k]
            cost += 10 * ca.sumsqr(error) + 2 * (1 - ca.cos(X[2, k + 1] - self.ref[2, k]))
            cost += 0.1 * w**2 + 0.5 * (limits.max_speed - v) ** 2 / steps
            if k > 0:
                cost += 2 * ca.sumsqr(U[:, k] - U[:, k - 1])
            gap = X[:2, k + 1] - self.obstacles  # (2, K) broadcast by repmat
            distance = ca.sqrt(ca.sum1(gap**2) + 1e-6)
            cost += 50 * ca.sumsqr(ca.fmax(0, limits.safe - distance))
        opti.minimize(cost)
        opti.subject_to(opti.bounded(0, U[0, :], limits.max_speed))
        opti.subject_to(opti.bounded(-limits.max_turn, U[1, :], limits.max_turn))
        # IPOPT stops within two control periods; solve_limited then takes its best iterate
        budget: dict[str, Any] = {
            "print_level": 0,
            "sb": "yes",
            "max_iter": 60,
            "max_wall_time": 2 * dt,
        }
        opti.solver("ipopt", {"print_time": False}, budget)
        self.guess = (np.zeros((3, steps + 1)), np.zeros((2, steps)))

    def solve(self, pose: Any, ref: Any, obstacles: Any) -> tuple[float, float]:
        """The first control (v, w) of the optimal plan from ``pose`` (3,) along ``ref``
        (3, N), clear of ``obstacles`` (2, K); warm-started from the last solution."""
        opti = self.opti
        opti.set_value(self.pose, pose)
        opti.set_value(self.ref, ref)
        opti.set_value(self.obstacles, obstacles)
        opti.set_initial(self.states, self.guess[0])
        opti.set_initial(self.controls, self.guess[1])
        solution = opti.solve_limited()  # the best iterate when IPOPT stops early
        states = np.asarray(solution.value(self.states), dtype=np.float64)  # (3, N+1)
        controls = np.asarray(solution.value(self.controls), dtype=np.float64)  # (2, N)
        self.guess = (
            np.column_stack([states[:, 1:], states[:, -1:]]),
            np.column_stack([controls[:, 1:], controls[:, -1:]]),
        )
        return float(controls[0, 0]), float(controls[1, 0])
