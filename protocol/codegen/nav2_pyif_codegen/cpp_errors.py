"""Render constants.py's plugin types and nav2_core error tables as a C++ header
(bridge_plugin/include/nav2_pyif_bridge/protocol/nav2_errors.hpp): which exception names a
reply may carry, which a plugin of each type throws under their own name, and each type's
generic, host-failure and invalid error. The plugin's error mapping (client/error_mapping.cpp)
looks them up instead of repeating them, so a new exception or plugin type is one edit of
constants.py and a regeneration."""

from __future__ import annotations

from nav2_pyif_protocol.constants import (
    CONTROLLER_ERRORS,
    ERRORS_BY_PLUGIN,
    GENERIC_ERROR,
    HOST_FAILURE_ERROR,
    INVALID_ERROR,
    PLANNER_ERRORS,
    PROTOCOL_ERRORS,
    SMOOTHER_ERRORS,
    ErrorType,
    PluginType,
)

from nav2_pyif_codegen.cpp_codec import INCLUDE, camel, comment, cpp_file

PATH = f"bridge_plugin/include/{INCLUDE}/nav2_errors.hpp"
#: The nav2_core exceptions, in ErrorType's order (the protocol errors left out).
NAV2_ERRORS = [e for e in ErrorType if e not in PROTOCOL_ERRORS]
#: The exception family each error is named after, checked in this order (nav2_core's
#: InvalidPath is a controller and a smoother class: the controller's comes first).
FAMILIES = (
    (PluginType.CONTROLLER, CONTROLLER_ERRORS),
    (PluginType.GLOBAL_PLANNER, PLANNER_ERRORS),
    (PluginType.SMOOTHER, SMOOTHER_ERRORS),
)


def _kind(plugin: PluginType) -> str:
    return f"PluginKind::{camel(plugin.value)}"


def _error(error: ErrorType) -> str:
    return f"ErrorKind::{error.value}"


def _mask(errors: frozenset[ErrorType]) -> int:
    return sum(1 << i for i, e in enumerate(NAV2_ERRORS) if e in errors)


def _table(
    name: str, cpp_type: str, size: str, items: list[str], doc: str, notes: list[str] | None = None
) -> list[str]:
    """A constexpr std::array, one item a line (``notes``: a comment after each)."""
    return [
        "",
        *comment(doc, ""),
        f"inline constexpr std::array<{cpp_type}, {size}> {name} = {{",
        *(
            f"  {item},  // {note}" if note else f"  {item},"
            for item, note in zip(items, notes or [""] * len(items), strict=True)
        ),
        "};",
    ]


def nav2_errors_hpp() -> str:
    plugins = list(PluginType)
    body = [
        "",
        "// The plugin types, as configure's plugin_type names them.",
        "enum class PluginKind : std::uint8_t",
        "{",
        *(f"  {camel(p.value)}," for p in plugins),
        "};",
        f"inline constexpr std::size_t kPluginKindCount = {len(plugins)};",
        *_table(
            "kPluginKindNames",
            "std::string_view",
            "kPluginKindCount",
            [f'"{p.value}"' for p in plugins],
            "Wire names, by PluginKind.",
        ),
        "",
        *comment(
            "The nav2_core exception classes of Jazzy and Kilted, by name; the names are also "
            "the wire's error.type values (PROTOCOL.md section 7).",
            "",
        ),
        "enum class ErrorKind : std::uint8_t",
        "{",
        *(f"  {e.value}," for e in NAV2_ERRORS),
        "};",
        f"inline constexpr std::size_t kErrorKindCount = {len(NAV2_ERRORS)};",
        *_table(
            "kErrorKindNames",
            "std::string_view",
            "kErrorKindCount",
            [f'"{e.value}"' for e in NAV2_ERRORS],
            "Wire names, by ErrorKind.",
        ),
        *_table(
            "kErrorFamily",
            "PluginKind",
            "kErrorKindCount",
            [next(_kind(p) for p, family in FAMILIES if e in family) for e in NAV2_ERRORS],
            "The plugin type whose exceptions each ErrorKind is one of (InvalidPath: the "
            "controller's), by ErrorKind.",
        ),
        *_table(
            "kOwnErrors",
            "std::uint32_t",
            "kPluginKindCount",
            [f"0x{_mask(ERRORS_BY_PLUGIN[p]):08x}u" for p in plugins],
            "The ErrorKinds a plugin of each type (by PluginKind) throws under their own name, "
            "bit i for ErrorKind i; any other error type becomes the type's generic error.",
            [p.value for p in plugins],
        ),
    ]
    for name, table, doc in (
        ("kGenericError", GENERIC_ERROR, "catch-all exception"),
        (
            "kHostFailureError",
            HOST_FAILURE_ERROR,
            "exception when its host failed it (none alive, no reply in time, Unavailable)",
        ),
        ("kInvalidError", INVALID_ERROR, "exception when it cannot be configured"),
    ):
        body += _table(
            name,
            "ErrorKind",
            "kPluginKindCount",
            [_error(table[p]) for p in plugins],
            f"Each plugin type's {doc}, by PluginKind.",
        )
    assert len(NAV2_ERRORS) <= 32, "kOwnErrors is a 32-bit mask per plugin type"
    return cpp_file(
        "The plugin types and the nav2_core exceptions each throws (constants.py's "
        "ERRORS_BY_PLUGIN, GENERIC_ERROR, HOST_FAILURE_ERROR and INVALID_ERROR), as tables the "
        "plugin's error mapping (client/error_mapping.cpp) looks up.",
        ["<array>", "<cstddef>", "<cstdint>", "<string_view>"],
        body,
        source="constants.py",
    )


def files() -> dict[str, str]:
    return {PATH: nav2_errors_hpp()}
