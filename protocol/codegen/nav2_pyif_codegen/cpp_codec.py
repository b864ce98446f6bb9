"""Render the schema as the C++ message structs and their codec (bridge_plugin/).

One function per generated file; each returns the file's text. The generated code calls the
hand-written runtime in bridge_plugin/src/protocol (Writer, MapReader and the read_* / write
primitives, one per field kind). The envelopes, whose fields carry rules of their own (the
version first, the op from the body's type, either a body or an error), are rendered by
cpp_envelopes on the functions here.
"""

from __future__ import annotations

import dataclasses
import textwrap
from collections.abc import Iterable

from nav2_pyif_protocol.constants import (
    MAX_INPUTS,
    OPS_BY_PLUGIN,
    PROTOCOL_ERRORS,
    PROTOCOL_VERSION,
    BehaviorFailure,
    BehaviorStatus,
    ErrorType,
    Op,
    PluginType,
)
from nav2_pyif_protocol.schema import (
    BIN,
    BODIES,
    BOOL,
    CARRIES,
    COSTMAP_SENT,
    FLOAT,
    FLOAT6,
    FLOAT7,
    INT,
    OP_TIMEOUT,
    PARAMS,
    RESTORED,
    ROWS,
    SMOOTH_GRACE_S,
    STR,
    STR_MAP,
    STRUCT_DOCS,
    STRUCTS,
    UINT,
    UINT32,
    CostmapSent,
    Field,
    Timeout,
)

COMMAND = "python -m nav2_pyif_codegen.generate"
WIDTH = 100
INCLUDE = "nav2_pyif_bridge/protocol"
NAMESPACE = "nav2_pyif_bridge::protocol"

# kind -> (C++ type, initializer, reader, writer call with {v} value and {w} path)
_SCALARS: dict[str, tuple[str, str, str, str]] = {
    INT: ("std::int64_t", "{0}", "read_i64", "w.i64({v})"),
    UINT: ("std::uint64_t", "{0}", "read_u64", "w.u64({v})"),
    UINT32: ("std::uint32_t", "{0}", "read_u32", "w.u64({v})"),
    FLOAT: ("double", "{0.0}", "read_f64", "w.f64({v})"),
    BOOL: ("bool", "{false}", "read_bool", "w.boolean({v})"),
    STR: ("std::string", "", "read_str", "w.str({v}, {w})"),
    PARAMS: ("Params", "", "read_params", "write_params(w, {v}, {w})"),
    STR_MAP: ("StringMap", "", "read_str_map", "write_str_map(w, {v}, {w})"),
    FLOAT6: ("std::array<double, 6>", "{}", "read_f64_array<6>", "w.floats({v})"),
    FLOAT7: ("std::array<double, 7>", "{}", "read_f64_array<7>", "w.floats({v})"),
}
_READ_PARAMS = "const Object & object, const FieldPath & where"
# Kinds whose reading or writing names the field in errors (so the path is needed).
_NAMED_KINDS = {STR, PARAMS, STR_MAP}

#: every op some call may carry
_CARRIED_OPS = frozenset(op for carried in CARRIES.values() for op in carried)


def header(purpose: str, source: str = "schema.py") -> str:
    """The first lines of every generated file: where it comes from, and what it is."""
    lines = [
        f"// Generated from protocol/nav2_pyif_protocol/{source} by",
        f"// `{COMMAND}`: do not edit.",
        "//",
        *comment(purpose, ""),
    ]
    return "\n".join(lines) + "\n"


def cpp_file(
    purpose: str,
    includes: list[str],
    body: list[str],
    *,
    namespace: str = NAMESPACE,
    source_of: str = "",
    source: str = "schema.py",
) -> str:
    """A generated C++ file: the header comment, then ``#pragma once`` (a header) or the
    include of ``source_of`` (a source file), the includes (system ones first), and ``body``
    inside ``namespace``."""
    out = [
        header(purpose, source),
        f'#include "{source_of}"' if source_of else "#pragma once",
        "",
    ]
    for group in (
        sorted(i for i in includes if i.startswith("<")),
        [i for i in includes if not i.startswith("<")],
    ):
        if group:
            out += [*(f"#include {i}" for i in group), ""]
    out += [f"namespace {namespace}", "{", *body, "", f"}}  // namespace {namespace}", ""]
    return "\n".join(out)


def comment(text: str, indent: str) -> list[str]:
    return textwrap.wrap(
        text, WIDTH, initial_indent=indent + "// ", subsequent_indent=indent + "// "
    )


def rule(title: str) -> str:
    """A section rule as wide as the code: `// --- title ------`."""
    text = f"// --- {title} "
    return text + "-" * (WIDTH - len(text))


def senders(op: Op, joiner: str) -> str:
    """The plugin types that send ``op``, for a comment or a table cell."""
    kinds = [p.value for p in PluginType if op in OPS_BY_PLUGIN[p]]
    return "every plugin type" if len(kinds) == len(PluginType) else joiner.join(kinds)


def camel(name: str) -> str:
    return "".join(part[:1].upper() + part[1:] for part in name.split("_"))


def snake(name: str) -> str:
    out = ""
    for i, c in enumerate(name):
        if c.isupper() and i:
            out += "_"
        out += c.lower()
    return out


def body_name(op: Op, direction: str) -> str:
    return camel(op.value) + direction


def row_constant(rows: str) -> str:
    return f"k{rows}RowSize"


def is_struct(kind: str) -> bool:
    return kind in STRUCTS


def cpp_type(f: Field) -> str:
    if is_struct(f.kind):
        base = f.kind
    elif f.kind == BIN:
        base = "std::vector<double>" if f.rows else "std::vector<std::uint8_t>"
    else:
        base = _SCALARS[f.kind][0]
    if f.many:
        base = f"std::vector<{base}>"
    return base if f.required else f"std::optional<{base}>"


def initializer(f: Field) -> str:
    if not f.required or is_struct(f.kind) or f.kind == BIN or f.many:
        return ""
    if f.default:
        return "{" + ", ".join(repr(float(x)) for x in f.default) + "}"
    if f.minimum is not None:
        return f"{{{f.minimum}}}"
    return _SCALARS[f.kind][1]


def reader(f: Field) -> str:
    """The read_* function of a field's kind: read_array of its element's for an array, and
    wrapped in read_at_least when the schema gives it a minimum."""
    if f.many:
        return f"read_array<{reader(dataclasses.replace(f, many=False))}>"
    if is_struct(f.kind):
        read = f"read_{snake(f.kind)}"
    elif f.kind == BIN:
        read = f"read_rows<{row_constant(f.rows)}>" if f.rows else "read_bin"
    else:
        read = _SCALARS[f.kind][2]
    return read if f.minimum is None else f"read_at_least<{read}, {f.minimum}>"


def uses_path(f: Field) -> bool:
    """Whether writing the field needs its path (for an EncodeError naming it)."""
    return is_struct(f.kind) or bool(f.rows) or f.kind in _NAMED_KINDS or f.many


def write_call(f: Field, value: str) -> str:
    path = f'where.key("{f.name}")'
    if is_struct(f.kind) or f.many:
        return f"write(w, {value}, {path})"
    if f.kind == BIN:
        if f.rows:
            return f"w.rows({value}, {row_constant(f.rows)}, {path})"
        return f"w.bin({value})"
    return _SCALARS[f.kind][3].format(v=value, w=path)


def statement(text: str, indent: str, hang: str = "    ") -> list[str]:
    """One statement, broken after a comma or before a `+` when it is wider than WIDTH."""
    line = indent + text
    if len(line) <= WIDTH:
        return [line]
    out: list[str] = []
    current = indent
    for piece in _pieces(text):
        if len(current) + len(piece) > WIDTH and current.strip():
            out.append(current.rstrip())
            current = indent + hang + piece.lstrip()
        else:
            current += piece
    out.append(current.rstrip())
    return out


def signature(head: str, params: str, tail: str = "") -> list[str]:
    """`head(params)tail`, with the parameters on their own line when it is too wide."""
    line = f"{head}({params}){tail}"
    return [line] if len(line) <= WIDTH else [f"{head}(", f"  {params}){tail}"]


def _pieces(text: str) -> Iterable[str]:
    start = 0
    depth = 0
    for i, c in enumerate(text):
        if c in "({<":
            depth += 1
        elif c in ")}>":
            depth -= 1
        elif c == "," and depth <= 1:
            yield text[start : i + 1]
            start = i + 1
        elif c == "+" and text[i - 1] == " ":
            yield text[start : i - 1]
            start = i - 1
    yield text[start:]


def struct_order() -> list[str]:
    """STRUCTS in an order where each comes after the structures it contains."""
    done: list[str] = []

    def visit(name: str) -> None:
        if name in done:
            return
        for f in STRUCTS[name]:
            if is_struct(f.kind):
                visit(f.kind)
        done.append(name)

    for name in STRUCTS:
        visit(name)
    return done


def all_types() -> list[tuple[str, tuple[Field, ...]]]:
    """Every generated struct: the structures, then each op's request and reply body."""
    out = [(name, STRUCTS[name]) for name in struct_order()]
    for op, (request, reply) in BODIES.items():
        out += [(body_name(op, "Request"), request), (body_name(op, "Reply"), reply)]
    return out


# --- headers --------------------------------------------------------------------------------


def _one_per_line(head: str, terms: list[str], joiner: str, end: str) -> list[str]:
    """``head`` and ``terms`` joined by ``joiner``, one term per line, aligned under the first;
    ``end`` after the last."""
    indent = " " * len(head)
    return [
        (head if i == 0 else indent) + term + (joiner if i < len(terms) - 1 else end)
        for i, term in enumerate(terms)
    ]


def _restored_count() -> int:
    return sum(len(ops) for ops in RESTORED.values())


def ops_hpp() -> str:
    body = [
        "",
        *comment(
            "The enumerator order is also the order of the alternatives of RequestBody and "
            "ReplyBody (bodies.hpp), so a body's variant index *is* its op.",
            "",
        ),
        "enum class Op : std::uint8_t",
        "{",
    ]
    for op in Op:
        body.append(f"  {camel(op.value)},  // {senders(op, ' and ')}")
    body += [
        "};",
        "",
        f"inline constexpr std::size_t kOpCount = {len(Op)};",
        "",
        "inline constexpr std::array<std::string_view, kOpCount> kOpNames = {",
        *(f'  "{op.value}",' for op in Op),
        "};",
        "",
        "constexpr std::string_view op_name(Op op) noexcept",
        "{",
        "  return kOpNames[static_cast<std::size_t>(op)];",
        "}",
        "",
        *comment(
            "Which of a plugin's timeouts bounds each op's reply (schema.py OP_TIMEOUT; "
            "PROTOCOL.md section 8).",
            "",
        ),
        "enum class TimeoutClass : std::uint8_t",
        "{",
        *(f"  {camel(t.value)}," for t in Timeout),
        "};",
        "",
        "inline constexpr std::array<TimeoutClass, kOpCount> kOpTimeout = {",
        *(f"  TimeoutClass::{camel(OP_TIMEOUT[op].value)},  // {op.value}" for op in Op),
        "};",
        "",
        "constexpr TimeoutClass timeout_class(Op op) noexcept",
        "{",
        "  return kOpTimeout[static_cast<std::size_t>(op)];",
        "}",
        "",
        *comment(
            "smooth gives the smoother max_time: the reply is awaited that long and this much "
            "more [s], or the plan timeout when that is longer (schema.py SMOOTH_GRACE_S).",
            "",
        ),
        f"inline constexpr double kSmoothGraceS = {SMOOTH_GRACE_S!r};",
        "",
        *comment(
            "Whether each op's request carries the plugin's costmap (schema.py COSTMAP_SENT, "
            "from the request's costmap field; PROTOCOL.md section 5).",
            "",
        ),
        "enum class CostmapSent : std::uint8_t",
        "{",
        *(f"  {camel(c.value)}," for c in CostmapSent),
        "};",
        "",
        "inline constexpr std::array<CostmapSent, kOpCount> kOpCostmap = {",
        *(f"  CostmapSent::{camel(COSTMAP_SENT[op].value)},  // {op.value}" for op in Op),
        "};",
        "",
        "constexpr CostmapSent costmap_sent(Op op) noexcept",
        "{",
        "  return kOpCostmap[static_cast<std::size_t>(op)];",
        "}",
        "",
        *comment(
            "What a new session on the host is sent again after configure (and activate), "
            "per plugin type, in this order (schema.py RESTORED; PROTOCOL.md section 4).",
            "",
        ),
        f"inline constexpr std::array<std::pair<PluginKind, Op>, {_restored_count()}> "
        "kRestored = {{",
        *(
            f"  {{PluginKind::{camel(plugin.value)}, Op::{camel(op.value)}}},"
            for plugin, ops in RESTORED.items()
            for op in ops
        ),
        "}};",
        "",
        *comment(
            "Whether a plugin type sends or answers a call of the carried control cycle "
            "(schema.py CARRIES; PROTOCOL.md section 15): the plugins of such types in one "
            "controller_server share its carried cycle.",
            "",
        ),
        "constexpr bool in_carried_cycle(PluginKind kind) noexcept",
        "{",
        *_one_per_line(
            "  return ",
            [
                f"kind == PluginKind::{camel(p.value)}"
                for p in PluginType
                if any(op in CARRIES or op in _CARRIED_OPS for op in OPS_BY_PLUGIN[p])
            ],
            " ||",
            ";",
        ),
        "}",
        "",
        "// std::nullopt for a name this version of the protocol does not know.",
        "constexpr std::optional<Op> op_from_name(std::string_view name) noexcept",
        "{",
        "  for (std::size_t i = 0; i < kOpCount; ++i) {",
        "    if (kOpNames[i] == name) {",
        "      return static_cast<Op>(i);",
        "    }",
        "  }",
        "  return std::nullopt;",
        "}",
    ]
    return cpp_file(
        "The operations of the protocol and their wire names (the request's `op`, also the "
        "last chunk of the Zenoh key `P/rpc/<op>`), and each op's traits.",
        [
            "<array>",
            "<cstddef>",
            "<cstdint>",
            "<optional>",
            "<string_view>",
            "<utility>",
            '"nav2_pyif_bridge/protocol/nav2_errors.hpp"',
        ],
        body,
    )


def constants_hpp() -> str:
    body = [
        "",
        "// Sent in every request and reply. Decoders refuse any other value (VersionMismatch).",
        f"inline constexpr std::int64_t kProtocolVersion = {PROTOCOL_VERSION};",
        "",
        "// The input names one session may send (a controller's `inputs` parameter): the host",
        "// keeps the latest message of each.",
        f"inline constexpr std::size_t kMaxInputs = {MAX_INPUTS};",
        "",
        *comment(
            "The protocol's own error types (error.type). The nav2_core exception names travel "
            "as plain strings too; mapping them to exceptions is the plugin's job "
            "(client/error_mapping.hpp).",
            "",
        ),
        "namespace error_type",
        "{",
        *(
            f'inline constexpr std::string_view k{e.value} = "{e.value}";'
            for e in ErrorType
            if e in PROTOCOL_ERRORS
        ),
        "}  // namespace error_type",
        "",
        "// std::nullopt for a name not in `names` (the wire's spelling, by enumerator).",
        "template<class Enum, std::size_t N>",
        "constexpr std::optional<Enum> from_name(",
        "  const std::array<std::string_view, N> & names, std::string_view name) noexcept",
        "{",
        "  for (std::size_t i = 0; i < N; ++i) {",
        "    if (names[i] == name) {",
        "      return static_cast<Enum>(i);",
        "    }",
        "  }",
        "  return std::nullopt;",
        "}",
    ]
    for enum, names in (
        (BehaviorStatus, "kBehaviorStatusNames"),
        (BehaviorFailure, "kBehaviorFailureNames"),
    ):
        assert enum.__doc__ is not None
        body += [
            "",
            *comment(" ".join(enum.__doc__.split()), ""),
            f"enum class {enum.__name__} : std::uint8_t",
            "{",
            *(f"  {camel(e.name.lower())}," for e in enum),
            "};",
            f"inline constexpr std::array<std::string_view, {len(enum)}> {names} = {{",
            *(f'  "{e.value}",' for e in enum),
            "};",
        ]
    return cpp_file(
        "Names every party of the protocol shares: the version, the error types and a "
        "behaviour's status and failure names (PROTOCOL.md sections 3, 7 and 17).",
        ["<array>", "<cstddef>", "<cstdint>", "<optional>", "<string_view>"],
        body,
        source="constants.py",
    )


def _struct(name: str, fields: tuple[Field, ...], doc: str) -> list[str]:
    out = comment(doc, "") if doc else []
    if not fields:
        return [*out, f"struct {name} {{}};"]
    out += [f"struct {name}", "{"]
    for f in fields:
        out += comment(f.doc if f.required else f"optional: {f.doc}", "  ")
        out.append(f"  {cpp_type(f)} {f.name}{initializer(f)};")
    for f in fields:
        if f.rows:
            count = f"{snake(f.rows)}_count"
            out += [
                "",
                f"  // Rows of {f.name} ({row_constant(f.rows)} values each).",
                f"  std::size_t {count}() const noexcept "
                f"{{return {f.name}.size() / {row_constant(f.rows)};}}",
            ]
    out.append("};")
    return out


def types_hpp() -> str:
    body = ["", "// Values per row of the packed float64 arrays (PROTOCOL.md section 2)."]
    for rows, (size, what) in ROWS.items():
        body.append(f"inline constexpr std::size_t {row_constant(rows)} = {size};  // {what}")
    for name in struct_order():
        body += ["", *_struct(name, STRUCTS[name], STRUCT_DOCS.get(name, ""))]
    return cpp_file(
        'The structures shared by several messages (PROTOCOL.md section 13, "Structures"). '
        "Plain data: the codec checks them when encoding. Units are SI; stamps are integer "
        "nanoseconds.",
        ["<array>", "<cstddef>", "<cstdint>", "<string>", "<vector>"],
        body,
    )


def bodies_hpp() -> str:
    body: list[str] = []
    for op, (request, reply) in BODIES.items():
        body += ["", rule(op.value)]
        body += _struct(body_name(op, "Request"), request, "")
        body += ["", *_struct(body_name(op, "Reply"), reply, "")]
    for direction in ("Request", "Reply"):
        names = ", ".join(body_name(op, direction) for op in Op)
        body += [
            "",
            "// Alternative i belongs to Op(i).",
            *statement(f"using {direction}Body = std::variant<{names}>;", "", "  "),
        ]
    body += [
        "",
        *(
            f"inline Op op_of(const {d}Body & body) noexcept "
            "{return static_cast<Op>(body.index());}"
            for d in ("Request", "Reply")
        ),
        "",
        "static_assert(std::variant_size_v<RequestBody> == kOpCount);",
        "static_assert(std::variant_size_v<ReplyBody> == kOpCount);",
        "",
        "// The reply body of each request body: ReplyOf<SmoothRequest> is SmoothReply.",
        "template<class Request>",
        "struct ReplyOfT;",
        *(
            line
            for op in Op
            for line in (
                f"template<> struct ReplyOfT<{body_name(op, 'Request')}>",
                f"{{using type = {body_name(op, 'Reply')};}};",
            )
        ),
        "template<class Request>",
        "using ReplyOf = typename ReplyOfT<Request>::type;",
    ]
    return cpp_file(
        "The operation-specific bodies of requests and replies (PROTOCOL.md section 13, "
        '"Operations"). Ops with an empty body still get their own (empty) type, so that a '
        "body's type alone says which op it belongs to.",
        [
            "<cstdint>",
            "<optional>",
            "<string>",
            "<variant>",
            "<vector>",
            *own("ops", "params", "types"),
        ],
        body,
    )


def fields_hpp() -> str:
    body: list[str] = []
    for name, fields in all_types():
        body += ["", "template<class Visit>"]
        if not fields:
            body.append(f"void for_each_field(const {name} &, Visit &&) {{}}")
            continue
        body += [f"void for_each_field(const {name} & value, Visit && visit)", "{"]
        body += [f'  visit("{f.name}", value.{f.name});' for f in fields]
        body.append("}")
    return cpp_file(
        "for_each_field(message, visit) calls visit(name, value) for each field of a structure "
        "or body, in wire order (optional fields as std::optional, present or not): for code "
        "that treats every message alike, such as the codec tests' JSON trees.",
        own("bodies", "types"),
        body,
    )


def own(*names: str) -> list[str]:
    return [f'"{INCLUDE}/{name}.hpp"' for name in names]


# --- the codec ------------------------------------------------------------------------------


def body_codec_hpp() -> str:
    body = ["", "// Writes one map, its keys in schema order; throws EncodeError naming the field."]
    for name, _ in all_types():
        body.append(f"void write(Writer & w, const {name} & value, const FieldPath & where);")
    body += [
        *(
            f"void write(Writer & w, const {d}Body & body, const FieldPath & where);"
            for d in ("Request", "Reply")
        ),
        "",
        "// An array field (`many` in the schema): each element written as its kind.",
        "template<class T>",
        "void write(Writer & w, const std::vector<T> & values, const FieldPath & where)",
        "{",
        "  w.array(values.size());",
        "  for (std::size_t i = 0; i < values.size(); ++i) {",
        "    write(w, values[i], where.index(i));",
        "  }",
        "}",
        "",
        "// Reads one map, checking every field; throws DecodeError naming the field.",
    ]
    for name, _ in all_types():
        body += signature(f"{name} read_{snake(name)}", _READ_PARAMS, ";")
    body += [
        *(
            f"{d}Body read_{d.lower()}_body(Op op, const Object & object, const FieldPath & where);"
            for d in ("Request", "Reply")
        ),
        "",
        "// Bytes of the variable-length fields (text, bin), to reserve before encoding.",
        *(f"std::size_t payload_size(const {name} & value);" for name, _ in all_types()),
        *(f"std::size_t payload_size(const {d}Body & body);" for d in ("Request", "Reply")),
        "inline std::size_t payload_size(const std::string & text) {return text.size();}",
        "template<class T>",
        "std::size_t payload_size(const std::vector<T> & values)",
        "{",
        "  std::size_t bytes = 0;",
        "  for (const auto & value : values) {",
        "    bytes += payload_size(value);",
        "  }",
        "  return bytes;",
        "}",
    ]
    return cpp_file(
        "Encode and decode every structure and op body of the schema (the envelopes, "
        "envelopes.cpp, call these).",
        [
            "<cstddef>",
            "<string>",
            "<vector>",
            *own("bodies", "types"),
            '"field_path.hpp"',
            '"reader.hpp"',
            '"writer.hpp"',
        ],
        body,
        namespace=f"{NAMESPACE}::detail",
    )


def _write_fn(name: str, fields: tuple[Field, ...]) -> list[str]:
    named = any(uses_path(f) or f.cells for f in fields)
    value = " value" if fields else ""
    where = " where" if named else ""
    out = [f"void write(Writer & w, const {name} &{value}, const FieldPath &{where})", "{"]
    for f in fields:
        if f.cells:
            sizes = ", ".join(f"value.{d}" for d in f.cells)
            out += statement(
                f'require_cells(value.{f.name}.size(), {{{sizes}}}, where.key("{f.name}"));', "  "
            )
    required = sum(1 for f in fields if f.required)
    optional = [f"(value.{f.name} ? 1u : 0u)" for f in fields if not f.required]
    if optional:
        out += statement(f"w.map(std::size_t{{{required}}} + {' + '.join(optional)});", "  ")
    else:
        out.append(f"  w.map({required});")
    for f in fields:
        if f.required:
            out += [
                f'  w.key("{f.name}");',
                *statement(write_call(f, f"value.{f.name}") + ";", "  "),
            ]
        else:
            out += [
                f"  if (value.{f.name}) {{",
                f'    w.key("{f.name}");',
                *statement(write_call(f, f"*value.{f.name}") + ";", "    "),
                "  }",
            ]
    out.append("}")
    return out


def _read_fn(name: str, fields: tuple[Field, ...]) -> list[str]:
    fn = signature(f"{name} read_{snake(name)}", _READ_PARAMS)
    if not fields:
        return [
            *fn,
            "{",
            "  static_cast<void>(MapReader(object, where));  // a map, even when empty",
            f"  return {name}{{}};",
            "}",
        ]
    out = [*fn, "{", "  const MapReader m(object, where);", f"  {name} out;"]
    for f in fields:
        how = "required" if f.required else "optional"
        out += statement(f'out.{f.name} = m.{how}("{f.name}", {reader(f)});', "  ")
    for f in fields:
        if f.cells:
            sizes = ", ".join(f"out.{d}" for d in f.cells)
            out += statement(
                f'expect_cells(out.{f.name}.size(), {{{sizes}}}, where.key("{f.name}"));', "  "
            )
    out += ["  return out;", "}"]
    return out


def payload_term(f: Field, of: str = "value") -> str | None:
    """The bytes of ``of``'s field ``f`` that payload_size counts, or None (a fixed size)."""
    value = f"{of}.{f.name}" if f.required else f"(*{of}.{f.name})"
    if is_struct(f.kind) or f.many:
        term = f"payload_size({value})"
    elif f.kind == BIN and f.rows:
        term = f"{value}.size() * 8"
    elif f.kind in (BIN, STR):
        term = f"{value}.size()"
    else:
        return None
    return term if f.required else f"({of}.{f.name} ? {term} : 0)"


def _payload_fn(name: str, fields: tuple[Field, ...]) -> list[str]:
    terms = [t for t in (payload_term(f) for f in fields) if t]
    if not terms:
        return [f"std::size_t payload_size(const {name} &) {{return 0;}}"]
    return [
        f"std::size_t payload_size(const {name} & value)",
        "{",
        *statement(f"return {' + '.join(terms)};", "  ", "         "),
        "}",
    ]


def body_codec_cpp() -> str:
    out = ["", rule("encode")]
    for name, fields in all_types():
        out += ["", *_write_fn(name, fields)]
    for direction in ("Request", "Reply"):
        out += [
            "",
            f"void write(Writer & w, const {direction}Body & body, const FieldPath & where)",
            "{",
            "  std::visit([&](const auto & alternative) {write(w, alternative, where);}, body);",
            "}",
        ]
    out += ["", rule("decode")]
    for name, fields in all_types():
        out += ["", *_read_fn(name, fields)]
    for direction in ("Request", "Reply"):
        out += [
            "",
            f"{direction}Body read_{direction.lower()}_body("
            "Op op, const Object & object, const FieldPath & where)",
            "{",
            "  switch (op) {",
        ]
        for op in Op:
            out += [
                f"    case Op::{camel(op.value)}:",
                f"      return read_{snake(body_name(op, direction))}(object, where);",
            ]
        out += [
            "  }",
            '  fail(where, "unknown op");  // unreachable: every Op is handled above',
            "}",
        ]
    out += ["", rule("sizes")]
    for name, fields in all_types():
        out += ["", *_payload_fn(name, fields)]
    for direction in ("Request", "Reply"):
        out += [
            "",
            f"std::size_t payload_size(const {direction}Body & body)",
            "{",
            "  return std::visit([](const auto & alternative) {return payload_size(alternative);}, "
            "body);",
            "}",
        ]
    return cpp_file(
        "Encode and decode every structure and op body of the schema, on the hand-written "
        "primitives of writer.hpp and reader.hpp (PROTOCOL.md section 2's canonical form).",
        ["<variant>"],
        out,
        namespace=f"{NAMESPACE}::detail",
        source_of="body_codec.hpp",
    )


def files() -> dict[str, str]:
    """Path (from the repository root) -> generated text, for every C++ file."""
    include = f"bridge_plugin/include/{INCLUDE}"
    return {
        f"{include}/constants.hpp": constants_hpp(),
        f"{include}/ops.hpp": ops_hpp(),
        f"{include}/types.hpp": types_hpp(),
        f"{include}/bodies.hpp": bodies_hpp(),
        f"{include}/fields.hpp": fields_hpp(),
        "bridge_plugin/src/protocol/body_codec.hpp": body_codec_hpp(),
        "bridge_plugin/src/protocol/body_codec.cpp": body_codec_cpp(),
    }
