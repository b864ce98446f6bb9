"""Per-call timing, for latency tables (transport vs planner compute)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class CallRecord:
    op: str
    total_ns: int  # client-side round trip: encode, Zenoh get, decode
    compute_ns: int  # host-side handler time, as the host reported it
    request_bytes: int
    ok: bool
    costmap_sent: bool = False
    plugin: str = ""  # which plugin made it (the runner: its role, e.g. "planner")

    @property
    def transport_ns(self) -> int:
        return max(0, self.total_ns - self.compute_ns)
