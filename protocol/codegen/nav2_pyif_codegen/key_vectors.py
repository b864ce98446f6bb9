"""The key rules as a shared vector (protocol/vectors/keys.json): every op's key, the cancel,
host and token keys under a prefix, and which prefixes are refused with which message, all
produced by ``nav2_pyif_protocol.keys``. The C++ KeySpace replays it
(bridge_plugin/test/client/keys_test.cpp), so the two builders of the same keys cannot drift
apart; ``nav2-pyif-vectors --check`` fails when keys.py changes and the vector does not.
"""

from __future__ import annotations

import json
from typing import Any

from nav2_pyif_protocol.constants import Op
from nav2_pyif_protocol.keys import KeySpace, validate_prefix

PREFIX = "nav2_pyif/robot1/FollowPath"
HOST = "vm-4f2a-host1"

#: Prefixes a plugin may be given: each refused (with its message) or accepted.
PREFIXES = [
    "",
    "/a",
    "a/",
    "a//b",
    "a/*/b",
    "a/**",
    "a/$x",
    "a?",
    "a/#",
    "0/chatter",
    "42/a/b",
    "@ros2_lv/0",
    "a/@b",
    "single",
    "robot7/0/FollowPath",
    PREFIX,
]


def _refusal(prefix: str) -> str | None:
    try:
        validate_prefix(prefix)
    except ValueError as error:
        return str(error)
    return None


def keys_vector() -> dict[str, Any]:
    keys = KeySpace(PREFIX)
    token = keys.host_token(HOST)
    return {
        "prefix": PREFIX,
        "calls": {op.value: keys.call(op) for op in Op},
        "cancel": keys.cancel,
        "hosts": keys.hosts,
        "host_token": {"host": HOST, "key": token},
        "prefixes": [{"prefix": p, "refused": _refusal(p)} for p in PREFIXES],
    }


def rendered_keys() -> dict[str, bytes]:
    """Relative path -> content: keys.json."""
    text = json.dumps(keys_vector(), indent=1, ensure_ascii=False) + "\n"
    return {"keys.json": text.encode()}
