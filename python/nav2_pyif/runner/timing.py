"""How long the controller took per control cycle, against the control period and the plugin's
timeout. In lockstep the simulated clock waits for every reply, so slowness never changes the
verdict: it is reported here instead, with the cycles Nav2 would have failed."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from nav2_pyif.client.calls import CallRecord

#: The op whose round trip is the control cycle's wait (controller_server's computeControl).
CYCLE_OP = "compute_velocity_commands"


@dataclass(frozen=True)
class CycleTiming:
    lockstep: bool
    calls: int  # compute_velocity_commands calls made (failed ones too)
    median_ms: float  # round trip: what controller_server waits for
    p99_ms: float
    control_period_ms: float  # 1 / controller_frequency
    call_timeout_ms: float  # the plugin's timeout
    over_period: int  # calls longer than the control period
    over_timeout: int  # calls longer than the plugin's timeout: Nav2 fails those cycles

    @property
    def mode(self) -> str:
        return "lockstep" if self.lockstep else "real time"

    def as_dict(self) -> dict[str, Any]:
        return {
            "mode": self.mode,
            "calls": self.calls,
            "round_trip_median_ms": round(self.median_ms, 3),
            "round_trip_p99_ms": round(self.p99_ms, 3),
            "control_period_ms": round(self.control_period_ms, 3),
            "call_timeout_ms": round(self.call_timeout_ms, 3),
            "over_control_period": self.over_period,
            "over_call_timeout": self.over_timeout,
        }

    def line(self) -> str:
        """One report line: the mode, the figures, and what Nav2 would have made of them."""
        if self.lockstep:
            how = "lockstep (simulated time waited for every reply)"
            verdict = f"{self.over_timeout} over the timeout (Nav2 would fail those cycles)"
        else:
            how = "real time (a reply past the timeout failed its cycle)"
            verdict = f"{self.over_timeout} over the timeout"
        if not self.calls:
            return f"  {how}: no control cycle ran"
        return (
            f"  {how}: controller round trip median {self.median_ms:.1f} ms, p99 "
            f"{self.p99_ms:.1f} ms; of {self.calls} calls {self.over_period} over the control "
            f"period {self.control_period_ms:g} ms, {verdict} of {self.call_timeout_ms:g} ms"
        )


def cycle_timing(
    records: list[CallRecord], rate: float, call_timeout: float, lockstep: bool
) -> CycleTiming:
    """The controller's cycle calls among ``records``, judged against the period of ``rate``
    [Hz] and ``call_timeout`` [s]."""
    ms = np.array([r.total_ns / 1e6 for r in records if r.op == CYCLE_OP])
    period, timeout = 1000.0 / rate, call_timeout * 1000.0
    return CycleTiming(
        lockstep=lockstep,
        calls=len(ms),
        median_ms=float(np.median(ms)) if len(ms) else 0.0,
        p99_ms=float(np.percentile(ms, 99)) if len(ms) else 0.0,
        control_period_ms=period,
        call_timeout_ms=timeout,
        over_period=int((ms > period).sum()),
        over_timeout=int((ms > timeout).sum()),
    )
