"""Zenoh key expressions, built in one place (as rmw_zenoh does)."""

from __future__ import annotations

from dataclasses import dataclass

from nav2_pyif_protocol.constants import Op


def validate_prefix(prefix: str) -> str:
    """Check a plugin's key prefix (e.g. ``nav2_pyif/robot1/FollowPath``) and return it."""
    if not prefix or prefix.startswith("/") or prefix.endswith("/"):
        raise ValueError(f"key prefix {prefix!r} must be non-empty without leading/trailing '/'")
    for chunk in prefix.split("/"):
        if not chunk or any(c in chunk for c in "*$?#"):
            raise ValueError(f"key prefix {prefix!r} has an empty or wildcard chunk {chunk!r}")
        if chunk.startswith("@"):
            raise ValueError(
                f"key prefix {prefix!r}: chunk {chunk!r} starts with '@', reserved by Zenoh "
                "('@/' admin space) and rmw_zenoh ('@ros2_lv/' liveliness)"
            )
    if prefix.split("/", 1)[0].isdigit():
        raise ValueError(
            f"key prefix {prefix!r} starts with a number: rmw_zenoh's topics and services are "
            "keyed <ROS domain id>/..., so a prefix like that could meet ROS traffic on a shared "
            "router; start it with a name (e.g. nav2_pyif/...)"
        )
    return prefix


@dataclass(frozen=True)
class KeySpace:
    """The keys under one plugin instance's prefix.

    - ``{prefix}/rpc/{op}``   a call, answered in order by the planner's call thread;
    - ``{prefix}/cancel``      out-of-band ``cancel_plan``, answered at once while a call runs;
    - ``{prefix}/host/{id}``   liveliness token of each host serving the prefix.
    """

    prefix: str

    def __post_init__(self) -> None:
        validate_prefix(self.prefix)

    def call(self, op: Op | str) -> str:
        op_name = op.value if isinstance(op, Op) else op
        if op_name == Op.CANCEL_PLAN.value:
            return self.cancel
        return f"{self.prefix}/rpc/{op_name}"

    @property
    def calls(self) -> str:
        return f"{self.prefix}/rpc/*"

    @property
    def admin(self) -> str:
        """Every admin query under the prefix (``admin_reload``, ``admin_info``)."""
        return f"{self.prefix}/admin/*"

    @property
    def cancel(self) -> str:
        return f"{self.prefix}/cancel"

    def host_token(self, host_id: str) -> str:
        return f"{self.prefix}/host/{host_id}"

    @property
    def admin_reload(self) -> str:
        """Hot swap: ``nav2-pyif reload`` asks the host to load a new planner here."""
        return f"{self.prefix}/admin/reload"

    @property
    def admin_info(self) -> str:
        """What ``nav2-pyif hosts`` asks each host about the planner it serves here."""
        return f"{self.prefix}/admin/info"

    @property
    def admin_record(self) -> str:
        """What ``nav2-pyif record`` asks to start, renew and stop a live recording stream."""
        return f"{self.prefix}/admin/record"

    def record_stream(self, stream_id: str) -> str:
        """Where the host publishes a copy of each call to the live recorder ``stream_id``."""
        return f"{self.prefix}/record/{stream_id}"

    @property
    def hosts(self) -> str:
        return f"{self.prefix}/host/*"
