"""Render constants.py's plugin types and nav2_core error tables as a C++ header
(bridge_plugin/include/nav2_pyif_bridge/protocol/nav2_errors.hpp): which exception names a
reply may carry, which a plugin of each type throws under their own name, and each type's
generic, host-failure and invalid error. The plugin's error mapping (client/error_mapping.cpp)
looks them up instead of repeating them, so a new exception or plugin type is one edit of
constants.py and a regeneration."""

from __future__ import annotations

from collections.abc import Sequence

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

from nav2_pyif_codegen.cpp_codec import INCLUDE, camel, comment, cpp_file, header

PATH = f"bridge_plugin/include/{INCLUDE}/nav2_errors.hpp"
NAV2_THROW = "bridge_plugin/src/nav2/nav2_exceptions.cpp"
SMOOTHER_THROW = "bridge_plugin/src/nav2/smoother_exceptions.cpp"
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
    body += _lookups()
    assert len(NAV2_ERRORS) <= 32, "kOwnErrors is a 32-bit mask per plugin type"
    return cpp_file(
        "The plugin types and the nav2_core exceptions each throws (constants.py's "
        "ERRORS_BY_PLUGIN, GENERIC_ERROR, HOST_FAILURE_ERROR and INVALID_ERROR), as tables the "
        "plugin's error mapping (client/error_mapping.cpp) looks up.",
        ["<array>", "<cstddef>", "<cstdint>", "<optional>", "<string_view>"],
        body,
        source="constants.py",
    )


def _lookups() -> list[str]:
    """One constexpr function per table: what the plugin's error mapping calls."""
    out = [
        "",
        "template<class Kind>",
        "constexpr std::size_t row_of(Kind kind) noexcept {return static_cast<std::size_t>(kind);}",
    ]
    for signature, doc, expression in (
        (
            "std::string_view plugin_type_name(PluginKind kind)",
            "The wire's configure.plugin_type of a plugin type.",
            "kPluginKindNames[row_of(kind)]",
        ),
        (
            "std::string_view error_kind_name(ErrorKind kind)",
            "The exception's name (also its error.type on the wire).",
            "kErrorKindNames[row_of(kind)]",
        ),
        (
            "PluginKind plugin_kind_of(ErrorKind kind)",
            "The plugin type whose exceptions `kind` is one of (InvalidPath: the controller's).",
            "kErrorFamily[row_of(kind)]",
        ),
        (
            "bool belongs_to(ErrorKind kind, PluginKind plugin)",
            "Whether a plugin of type `plugin` throws `kind` under its own name.",
            "(kOwnErrors[row_of(plugin)] >> row_of(kind)) & 1u",
        ),
        (
            "ErrorKind generic_error(PluginKind kind)",
            "The plugin type's catch-all exception.",
            "kGenericError[row_of(kind)]",
        ),
        (
            "ErrorKind host_failure_error(PluginKind kind)",
            "What a plugin throws when its host, not its planner, failed the call (none alive, "
            "no reply in time, a broken transport, an Unavailable reply): the class Nav2's "
            "recovery conditions retry (RELIABILITY.md).",
            "kHostFailureError[row_of(kind)]",
        ),
        (
            "ErrorKind invalid_error(PluginKind kind)",
            "What a plugin throws when it cannot be configured.",
            "kInvalidError[row_of(kind)]",
        ),
    ):
        out += [
            "",
            *comment(doc, ""),
            f"constexpr {signature} noexcept",
            "{",
            f"  return {expression};",
            "}",
        ]
    return [
        *out,
        "",
        "// std::nullopt for a name that is no nav2_core exception (protocol errors included).",
        "constexpr std::optional<ErrorKind> error_kind_from_name(std::string_view name) noexcept",
        "{",
        "  for (std::size_t i = 0; i < kErrorKindCount; ++i) {",
        "    if (kErrorKindNames[i] == name) {",
        "      return static_cast<ErrorKind>(i);",
        "    }",
        "  }",
        "  return std::nullopt;",
        "}",
    ]


def _throws(errors: Sequence[ErrorType]) -> list[str]:
    return [f"    case ErrorKind::{e.value}: throw nav2_core::{e.value}(message);" for e in errors]


def nav2_exceptions_cpp() -> str:
    """throw_nav2_exception (nav2_api.hpp): one nav2_core class per ErrorKind. The smoother's
    are thrown from a file of their own: nav2_core's controller and smoother headers both
    define an InvalidPath."""
    own = [e for e in NAV2_ERRORS if e not in SMOOTHER_ERRORS or e in CONTROLLER_ERRORS]
    lines = [
        header(
            "Throw the nav2_core exception class an ErrorKind names (constants.py's error "
            "names are nav2_core's class names); the smoother's in smoother_exceptions.cpp.",
            "constants.py",
        ),
        '#include "nav2_pyif_bridge/nav2_api.hpp"',
        "",
        "#include <string>",
        "",
        '#include "nav2_pyif_bridge/smoother_exceptions.hpp"',
        "",
        "namespace nav2_pyif_bridge",
        "{",
        "",
        "void throw_nav2_exception(",
        "  client::PluginKind plugin, client::ErrorKind kind, const std::string & message)",
        "{",
        "#if NAV2_PYIF_JAZZY_API",
        "  using client::ErrorKind;",
        "  if (plugin == client::PluginKind::Smoother) {",
        "    throw_smoother_exception(kind, message);",
        "  }",
        "  switch (kind) {",
        *_throws(own),
        "    default: throw_smoother_exception(kind, message);",
        "  }",
        "#else",
        "  (void)plugin;",
        "  (void)kind;",
        "  throw nav2_core::PlannerException(message);",
        "#endif",
        "}",
        "",
        "}  // namespace nav2_pyif_bridge",
        "",
    ]
    return "\n".join(lines)


def smoother_exceptions_cpp() -> str:
    smoother = [
        e for e in NAV2_ERRORS if e in SMOOTHER_ERRORS and e is not ErrorType.SMOOTHER_EXCEPTION
    ]
    lines = [
        header(
            "Throw nav2_core's smoother exceptions (smoother_exceptions.hpp), apart from "
            "nav2_exceptions.cpp: nav2_core's smoother and controller headers both define an "
            "InvalidPath.",
            "constants.py",
        ),
        '#include "nav2_pyif_bridge/smoother_exceptions.hpp"',
        "",
        "#include <string>",
        "",
        "#if __has_include(<nav2_core/smoother_exceptions.hpp>)",
        "#  define NAV2_PYIF_HAS_SMOOTHER_EXCEPTIONS 1",
        '#  include "nav2_core/smoother_exceptions.hpp"',
        "#else",
        "#  define NAV2_PYIF_HAS_SMOOTHER_EXCEPTIONS 0",
        '#  include "nav2_core/exceptions.hpp"',
        "#endif",
        "",
        "namespace nav2_pyif_bridge",
        "{",
        "",
        "void throw_smoother_exception(client::ErrorKind kind, const std::string & message)",
        "{",
        "#if NAV2_PYIF_HAS_SMOOTHER_EXCEPTIONS",
        "  using client::ErrorKind;",
        "  switch (kind) {",
        *_throws(smoother),
        "    default: throw nav2_core::SmootherException(message);",
        "  }",
        "#else",
        "  // Humble has no smoother exceptions: its smoother_server catches PlannerException",
        "  (void)kind;",
        "  throw nav2_core::PlannerException(message);",
        "#endif",
        "}",
        "",
        "}  // namespace nav2_pyif_bridge",
        "",
    ]
    return "\n".join(lines)


def files() -> dict[str, str]:
    return {
        PATH: nav2_errors_hpp(),
        NAV2_THROW: nav2_exceptions_cpp(),
        SMOOTHER_THROW: smoother_exceptions_cpp(),
    }
