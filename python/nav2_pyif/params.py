"""Planner parameters: declared with defaults, given the Nav2 YAML's values, updated live.

The Nav2 plugin sends every parameter under its namespace at configure (``ros2 param set``
changes follow via set_parameters). A planner declares what it reads::

    self.max_speed = self.params.declare("max_speed", 0.5, "top linear speed [m/s]")

A given value must have the default's type (an int is accepted for a float); a bad update is
rejected with a reason and the old value stays. As in ROS 2, a parameter the planner never
declared (nor read) is not one of its parameters: given at configure it is reported back as
ignored (a misspelt name in the Nav2 YAML), and an update to it is rejected.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any, TypeVar

Scalar = bool | int | float | str
ParamValue = Scalar | list[bool] | list[int] | list[float] | list[str]
T = TypeVar("T", bool, int, float, str, list[bool], list[int], list[float], list[str])


@dataclass
class Declared:
    default: ParamValue
    description: str


def _coerce(name: str, value: Any, like: Any) -> Any:
    """``value`` converted to the type of ``like``, or TypeError saying why not."""
    if isinstance(like, list):
        if not isinstance(value, list):
            raise TypeError(f"{name}: expected a list, got {type(value).__name__}")
        if not like:
            return list(value)
        return [_coerce(f"{name}[{i}]", v, like[0]) for i, v in enumerate(value)]
    if isinstance(like, bool) or isinstance(value, bool):
        if type(value) is not type(like):
            raise TypeError(f"{name}: expected {type(like).__name__}, got {type(value).__name__}")
        return value
    if isinstance(like, float) and isinstance(value, (int, float)):
        return float(value)
    if type(value) is not type(like):
        raise TypeError(f"{name}: expected {type(like).__name__}, got {type(value).__name__}")
    return value


class Parameters:
    def __init__(self, given: dict[str, ParamValue] | None = None) -> None:
        self._values: dict[str, ParamValue] = dict(given or {})
        self._declared: dict[str, Declared] = {}
        self._read: set[str] = set()  # looked up without declaring: used all the same
        self._listeners: list[Callable[[dict[str, ParamValue]], None]] = []

    def declare(self, name: str, default: T, description: str = "") -> T:
        """Declare ``name`` and return its value: the given one if any, else ``default``.

        Raises TypeError when the given value has the wrong type (configure then fails with
        InvalidController / InvalidPlanner naming the parameter)."""
        self._declared[name] = Declared(default, description)
        value: T = _coerce(name, self._values[name], default) if name in self._values else default
        self._values[name] = value
        return value

    def __getitem__(self, name: str) -> Any:
        self._read.add(name)
        try:
            return self._values[name]
        except KeyError:
            raise KeyError(f"parameter {name!r} was neither given nor declared") from None

    def get(self, name: str, default: Any = None) -> Any:
        self._read.add(name)
        return self._values.get(name, default)

    def __contains__(self, name: object) -> bool:
        if isinstance(name, str):
            self._read.add(name)
        return name in self._values

    def as_dict(self) -> dict[str, ParamValue]:
        return dict(self._values)

    def declared(self) -> dict[str, ParamValue]:
        """Declared parameters with their current values (reported back to the plugin)."""
        return {name: self._values[name] for name in self._declared}

    def undeclared(self) -> dict[str, str]:
        """Given parameters the planner neither declared nor read (call after configure):
        name -> why it is ignored. The reasons leave out what the planner declares, which
        a warning of several names gives once (:func:`declares`)."""
        return {
            name: self._not_a_parameter(name, with_declared=False)
            for name in self._values
            if not self._known(name)
        }

    def _known(self, name: str) -> bool:
        return name in self._declared or name in self._read

    def _not_a_parameter(self, name: str, *, with_declared: bool = True) -> str:
        close = difflib.get_close_matches(name, sorted(self._declared), n=1)
        return (
            f"{name} is not a parameter of this planner"
            + (f" (did you mean {close[0]}?)" if close else "")
            + (f"; {declares(self._declared)}" if with_declared else "")
        )

    def description(self, name: str) -> str:
        return self._declared[name].description if name in self._declared else ""

    def on_change(self, listener: Callable[[dict[str, ParamValue]], None]) -> None:
        """Call ``listener(changed)`` after each accepted update."""
        self._listeners.append(listener)

    def update(
        self, changes: dict[str, ParamValue]
    ) -> tuple[dict[str, ParamValue], dict[str, str]]:
        """Apply changes; returns (applied, rejected name -> reason). Used by the host, after
        configure: a name the planner neither declared nor read is rejected, as in ROS 2."""
        applied: dict[str, ParamValue] = {}
        rejected: dict[str, str] = {}
        for name, value in changes.items():
            if not self._known(name):
                rejected[name] = self._not_a_parameter(name)
                continue
            try:
                if name in self._declared:
                    value = _coerce(name, value, self._declared[name].default)
            except TypeError as exc:
                rejected[name] = str(exc)
                continue
            self._values[name] = value
            applied[name] = value
        if applied:
            for listener in self._listeners:
                listener(applied)
        return applied, rejected


def declares(names: Iterable[str]) -> str:
    """What a planner declares, for a message: "it declares: a, b" (sorted; "none")."""
    return f"it declares: {', '.join(sorted(names)) or 'none'}"
