"""Hot swap from outside: ask the host serving a key to load another planner (or a fresh
import of the same one) without dropping the key. What ``nav2-pyif reload`` sends."""

from __future__ import annotations

import msgpack
import zenoh
from nav2_pyif_protocol.keys import KeySpace

from nav2_pyif.exceptions import PlannerLoadError


def request_reload(
    session: zenoh.Session,
    key_prefix: str,
    *,
    planner: str | None = None,
    module: str | None = None,
    delegates: dict[str, str] | None = None,
    timeout: float = 60.0,
) -> str:
    """Returns the host's confirmation; raises PlannerLoadError with the host's reason when
    it refused (the old planner keeps serving), TimeoutError when no host answered."""
    request = {"planner": planner, "module": module, "delegates": delegates}
    for reply in session.get(
        KeySpace(key_prefix).admin_reload, payload=msgpack.packb(request), timeout=timeout
    ):
        if reply.ok is None:
            continue
        answer = msgpack.unpackb(reply.ok.payload.to_bytes())
        if not answer.get("ok"):
            raise PlannerLoadError(str(answer.get("message")))
        return str(answer.get("message"))
    raise TimeoutError(f"no planner host answered a reload on {key_prefix} within {timeout} s")
