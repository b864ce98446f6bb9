"""ROS messages by type name, and their serialized (CDR) form: how inputs and debug outputs
travel between the C++ plugin, which handles them as bytes of a named type only
(rclcpp::GenericSubscription / GenericPublisher), and the host, where they are rclpy messages.
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import os
import re
import subprocess
import sys
from functools import cache
from pathlib import Path
from typing import Any

log = logging.getLogger("nav2_pyif._ros_types")


class MessageTypeError(ValueError):
    """A type name that is not ``package/msg/Type`` or names no importable message."""


#: rosidl's rules for a package's and a message's name
_PACKAGE_NAME = re.compile(r"[a-z][a-z0-9_]*\Z")
_MESSAGE_NAME = re.compile(r"[A-Z][A-Za-z0-9]*\Z")


def _module_name(message: str) -> str:
    """rosidl's module of a message: LaserScan -> _laser_scan, PointCloud2 -> _point_cloud2."""
    name = re.sub(r"(.)([A-Z][a-z]+)", r"\1_\2", message)
    return "_" + re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", name).lower()


def _is_message(package: str, message: str) -> bool:
    """Whether an installed ROS package generated this message (rosidl's layout:
    <package>/msg/_<message in snake case>.py), found without importing anything: a type name
    comes from the network, and importing a package runs its code."""
    module = sys.modules.get(package)
    try:
        spec = module.__spec__ if module is not None else importlib.util.find_spec(package)
    except (ImportError, ValueError):
        return False
    places = (spec.submodule_search_locations or []) if spec is not None else []
    return any((Path(place) / "msg" / f"{_module_name(message)}.py").is_file() for place in places)


@cache
def message_class(type_name: str) -> type:
    """``"sensor_msgs/msg/LaserScan"`` -> the rclpy message class (imported by its name, as
    rosidl_runtime_py.utilities.get_message does, without needing that package). Only a
    message an installed ROS package generated is imported."""
    parts = type_name.split("/")
    if len(parts) != 3 or parts[1] != "msg" or not all(parts):
        raise MessageTypeError(f"{type_name!r} is not a message type name (package/msg/Type)")
    package, _, name = parts
    if not (_PACKAGE_NAME.match(package) and _MESSAGE_NAME.match(name)):
        raise MessageTypeError(f"{type_name!r} is not a ROS message type name")
    if not _is_message(package, name):
        raise MessageTypeError(
            f"message type {type_name} is not available on this host (no installed package "
            f"{package} generated it); install its package (e.g. pip install "
            f"ros-jazzy-{package.replace('_', '-')})"
        )
    try:
        cls = getattr(importlib.import_module(f"{package}.msg"), name)
    except (ImportError, AttributeError) as exc:
        raise MessageTypeError(
            f"message type {type_name} is not available on this host ({exc}); install its "
            f"package (e.g. pip install ros-jazzy-{package.replace('_', '-')})"
        ) from None
    if not isinstance(cls, type):
        raise MessageTypeError(f"{type_name} is not a message class")
    return cls


def type_name_of(msg: Any) -> str:
    """The ``package/msg/Type`` name of an rclpy message."""
    cls = type(msg)
    package = cls.__module__.split(".")[0]
    return f"{package}/msg/{cls.__name__}"


#: Set to $RMW_IMPLEMENTATION once a child process loaded it (the host checks before its
#: workers start; they inherit the answer instead of each starting a probe of their own).
RMW_CHECKED = "NAV2_PYIF_RMW_CHECKED"


def _rmw_unchecked() -> bool:
    wanted = os.environ.get("RMW_IMPLEMENTATION")
    return bool(wanted) and os.environ.get(RMW_CHECKED) != wanted


@cache
def check_serialization_rmw() -> None:
    """rclpy's serialization loads an rmw implementation, and rcl ends the process (exit code
    102) when $RMW_IMPLEMENTATION names one this Python environment cannot load: a planner
    host started beside a Nav2 on rmw_zenoh, from an environment that has only the default
    rmw (an ament index may still list the other one, from the ROS install sourced beside).
    So a child process tries first, once; when it fails, the host serializes with the default
    rmw (it makes no ROS node, and every rmw writes the same CDR) and says so."""
    if not _rmw_unchecked():
        return
    wanted = os.environ["RMW_IMPLEMENTATION"]
    probe = subprocess.run(
        [sys.executable, "-c", "import rclpy.serialization"],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    if probe.returncode != 0:
        log.warning(
            "RMW_IMPLEMENTATION=%s cannot be loaded in this Python environment (%s); "
            "serializing ROS messages with the default rmw instead (the CDR is the same)",
            wanted,
            (probe.stderr.strip().splitlines() or [f"exit code {probe.returncode}"])[-1][:300],
        )
        del os.environ["RMW_IMPLEMENTATION"]
    else:
        os.environ[RMW_CHECKED] = wanted  # the workers, started after this, inherit it


def deserialize(type_name: str, cdr: bytes) -> Any:
    check_serialization_rmw()
    from rclpy.serialization import deserialize_message

    return deserialize_message(cdr, message_class(type_name))


def serialize(msg: Any) -> bytes:
    check_serialization_rmw()
    from rclpy.serialization import serialize_message

    return serialize_message(msg)  # type: ignore[no-any-return]


@cache
def warm_serialization() -> None:
    """Load rclpy's serialization and the rmw's type support once, now: the first message a
    process serializes costs 0.2 to 0.5 s of loading (measured here), which a controller's
    first control cycle with an input or a debug output cannot pay (it would overrun the
    control period, and a batch waiting on it drops its other robots' cycles). Later message
    types cost milliseconds. Without rclpy (a host with no ROS messages) there is nothing to
    warm: inputs and debug outputs say what is missing when used. Nor where the rmw of
    $RMW_IMPLEMENTATION was not checked yet (a process other than the host's): warming would
    start the check's child process in configure; the first input checks, as before."""
    if _rmw_unchecked():
        return
    try:
        serialize(message_class("std_msgs/msg/Header")())
    except (ImportError, MessageTypeError) as exc:
        log.debug("no ROS message serialization to warm up: %s", exc)
