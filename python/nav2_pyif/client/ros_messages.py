"""ROS messages to and from CDR for the client, safe under a command's signal handlers: rclpy's
C conversions call the message constructors, and a handler raising there (``Interrupted``)
comes out as "TypeError: Unable to convert function return value". A terminating signal waits
until the conversion is done (``deferred``), then is raised."""

from __future__ import annotations

from typing import Any

from nav2_pyif._ros_types import deserialize, serialize
from nav2_pyif.common.signals import deferred


def from_cdr(type_name: str, cdr: bytes) -> Any:
    with deferred():
        return deserialize(type_name, cdr)


def to_cdr(msg: Any) -> bytes:
    with deferred():
        return serialize(msg)
