"""Render the envelopes of the schema (REQUEST_ENVELOPE, REPLY_ENVELOPE) as the C++ Request
and Reply (messages.hpp) and their encode and decode (envelopes.cpp), on the body codec that
cpp_codec generates and the hand-written runtime of bridge_plugin/src/protocol.

An envelope field is written and read as its kind, like any field of a body; a few carry a
rule of their own, which the schema states and this module turns into C++ (PROTOCOL.md
section 13, "Envelopes"):

- ``Role.VERSION`` (``v``): a new message holds kProtocolVersion; decoders read it before any
  other field (the runtime's read_version: VersionMismatch for any other value).
- ``Role.OP`` (a request's ``op``): no member but an accessor, the op of the body's type, so
  the two cannot disagree; written by name, read by read_op, and the body is read as that
  op's. An envelope without one (a reply) is decoded for the op its caller names.
- a ``BODY`` field: the RequestBody / ReplyBody variant, written and read by the body codec
  under the path "<op> request body"; a missing one reads as {} (the runtime's body_map).
- ``selects`` (a reply's ``ok``): the two fields it selects are one std::variant, ``outcome``;
  the flag is an accessor saying which alternative it holds, and each field an accessor to
  its own. The selected field must be there, but for a BODY field, which reads as {}.
- ``minimum`` (a request's ``epoch``): where a new message starts; read with read_at_least.

Decoders read the version first, then the envelope's other fields in schema order, and the
body (or what the flag selects) last: the envelope is checked before the body, as the Python
codec does, so both codecs refuse the same messages with the same error types.
"""

from __future__ import annotations

import dataclasses

from nav2_pyif_protocol.schema import (
    BODY,
    BOOL,
    INT,
    REPLY_ENVELOPE,
    REQUEST_ENVELOPE,
    STR,
    Field,
    Role,
)

from nav2_pyif_codegen.cpp_codec import (
    INCLUDE,
    comment,
    cpp_file,
    cpp_type,
    initializer,
    is_struct,
    own,
    payload_term,
    reader,
    rule,
    signature,
    statement,
    write_call,
)

#: The member of Reply that holds the two fields its flag selects (body or error).
VARIANT = "outcome"
#: Bytes a Writer reserves for an envelope and a typical body; text and arrays come on top.
SMALL_MESSAGE = 512


@dataclasses.dataclass(frozen=True)
class Envelope:
    """One envelope of the schema and the fields its rules single out."""

    name: str  # the C++ struct: Request, Reply
    fields: tuple[Field, ...]
    version: Field
    body: Field
    op: Field | None  # the Role.OP field; None: the caller names the op (a reply)
    flag: Field | None  # the field with `selects`
    alternatives: tuple[Field, ...]  # what the flag selects: (when true, when false)

    @property
    def what(self) -> str:
        """The codec functions' suffix, their parameter and the root of paths: "request"."""
        return self.name.lower()


def envelope(name: str, fields: tuple[Field, ...]) -> Envelope:
    """The envelope ``fields`` as C++ ``name``; SystemExit for a rule this module lacks."""

    def refuse(problem: str) -> SystemExit:
        return SystemExit(
            f"the {name.lower()} envelope in schema.py {problem}: cpp_envelopes.py "
            "generates no C++ for that"
        )

    def one(what: str, found: list[Field], kind: str | None = None) -> Field | None:
        if len(found) > 1:
            raise refuse(f"has {len(found)} {what} fields")
        if found and kind is not None and found[0].kind != kind:
            raise refuse(f"gives its {what} field `{found[0].name}` the kind {found[0].kind}")
        return found[0] if found else None

    version = one("version", [f for f in fields if f.role is Role.VERSION], INT)
    body = one("body", [f for f in fields if f.kind == BODY])
    op = one("op", [f for f in fields if f.role is Role.OP], STR)
    flag = one("selecting", [f for f in fields if f.selects], BOOL)
    if version is None or body is None:
        raise refuse("lacks a version (Role.VERSION) or a body (BODY) field")
    if op is not None and not op.required:
        raise refuse(f"makes its op field `{op.name}` optional")
    if not body.required and (flag is None or body.name not in (flag.selects or ())):
        raise refuse(f"makes its body `{body.name}` optional but selected by no flag")
    alternatives: tuple[Field, ...] = ()
    if flag is not None:
        assert flag.selects is not None
        names = [f.name for f in fields]
        if any(n not in names for n in flag.selects):
            raise refuse(f"selects {flag.selects} by `{flag.name}`, not all of them its fields")
        alternatives = tuple(fields[names.index(n)] for n in flag.selects)
        positions = [fields.index(f) for f in alternatives]
        if positions[1] != positions[0] + 1 or any(f.required for f in alternatives):
            raise refuse(f"selects {flag.selects} by `{flag.name}`: not two optional neighbours")
        if any(f.kind != BODY and not is_struct(f.kind) for f in alternatives):
            raise refuse(f"selects {flag.selects} by `{flag.name}`: not a body or a structure")
    return Envelope(name, fields, version, body, op, flag, alternatives)


def envelopes() -> list[Envelope]:
    return [envelope("Request", REQUEST_ENVELOPE), envelope("Reply", REPLY_ENVELOPE)]


def _type(env: Envelope, f: Field) -> str:
    """The C++ type of a field's value (a selected field's without std::optional)."""
    if f.kind == BODY:
        return f"{env.name}Body"
    return cpp_type(dataclasses.replace(f, required=f.required or f in env.alternatives))


def _value(env: Envelope, f: Field) -> str:
    """How encode_<what> reaches a field's value: a member, or an accessor."""
    access = f"{env.what}.{f.name}"
    return f"{access}()" if f in (env.op, env.flag, *env.alternatives) else access


# --- messages.hpp ---------------------------------------------------------------------------


def _struct(env: Envelope) -> list[str]:
    out = [f"struct {env.name}", "{"]
    accessors: list[str] = []
    for f in env.fields:
        if f is env.op:
            accessors += [
                *comment(
                    f"{f.doc}: the op of the body's type, so that the wire's `{f.name}` and "
                    "the body never disagree.",
                    "  ",
                ),
                f"  Op {f.name}() const noexcept {{return op_of({env.body.name});}}",
            ]
        elif f is env.flag:
            assert env.flag is not None
            accessors += [
                *comment(f.doc, "  "),
                f"  bool {f.name}() const noexcept {{return {VARIANT}.index() == 0;}}",
                *comment(
                    f"Throw std::bad_variant_access when called on the other kind of {env.what}.",
                    "  ",
                ),
                *(
                    f"  const {_type(env, a)} & {a.name}() const "
                    f"{{return std::get<{i}>({VARIANT});}}"
                    for i, a in enumerate(env.alternatives)
                ),
            ]
        elif f in env.alternatives:
            if f is env.alternatives[0]:
                first, second = env.alternatives
                assert env.flag is not None
                out += [
                    *comment(
                        f"The wire's `{env.flag.name}` with either `{first.name}` (true) or "
                        f"`{second.name}` (false): one of them, never both.",
                        "  ",
                    ),
                    f"  std::variant<{_type(env, first)}, {_type(env, second)}> {VARIANT};",
                ]
        else:
            init = (
                "{kProtocolVersion}"
                if f is env.version
                else ""
                if f.kind == BODY
                else initializer(f)
            )
            out += [
                *comment(f.doc if f.required else f"optional: {f.doc}", "  "),
                f"  {_type(env, f)} {f.name}{init};",
            ]
    return [*out, *([""] if accessors else []), *accessors, "};"]


def messages_hpp() -> str:
    body: list[str] = []
    for env in envelopes():
        body += ["", *_struct(env)]
    return cpp_file(
        'The envelopes (PROTOCOL.md section 13, "Envelopes"): what one Zenoh query carries '
        "(Request) and what its reply carries (Reply), with the op's body. Encode and decode "
        "them with codec.hpp.",
        ["<cstdint>", "<string>", "<variant>", *own("bodies", "constants", "ops", "types")],
        body,
    )


# --- envelopes.cpp --------------------------------------------------------------------------


def _body_path(env: Envelope, f: Field, op: str) -> str:
    """The path a body's errors are named by: "set_plan request body"."""
    return f'FieldPath({op}, " {env.what} {f.name}")'


def _write(env: Envelope, f: Field, op: str, indent: str) -> list[str]:
    """Key and value of a field that is there (an optional one's test is the caller's)."""
    value = _value(env, f) if f.required or f in env.alternatives else f"*{_value(env, f)}"
    if f.kind == BODY:
        call = f"write(w, {value}, {_body_path(env, f, op)})"
    elif f is env.op:
        call = "w.key(op)"  # an op's name is one of the schema's ASCII literals, like a key
    else:
        call = write_call(f, value)
    return [f'{indent}w.key("{f.name}");', *statement(call + ";", indent)]


def _encode(env: Envelope) -> list[str]:
    what = env.what
    op = "op" if env.op else f"op_name(op_of({_value(env, env.body)}))"
    sizes = ["kSmallMessage"]
    for f in env.fields:
        if f in (env.op, env.flag, *env.alternatives):
            continue
        term = f"payload_size({_value(env, f)})" if f.kind == BODY else payload_term(f, what)
        sizes += [term] if term else []
    if env.flag:
        when_true, when_false = (f"payload_size({_value(env, a)})" for a in env.alternatives)
        sizes.append(f"({_value(env, env.flag)} ? {when_true} : {when_false})")
    plain = [f for f in env.fields if f not in env.alternatives]
    count = sum(1 for f in plain if f.required) + (1 if env.alternatives else 0)
    optional = [f"({_value(env, f)} ? 1u : 0u)" for f in plain if not f.required]
    out = [f"Bytes encode_{what}(const {env.name} & {what})", "{"]
    if env.op:
        out.append(f"  const std::string_view op = op_name({_value(env, env.op)});")
    out += [f'  const FieldPath where("{what}");']
    out += statement(f"Writer w({' + '.join(sizes)});", "  ")
    entries = f"std::size_t{{{count}}} + {' + '.join(optional)}" if optional else str(count)
    out += statement(f"w.map({entries});", "  ")
    for f in env.fields:
        if f in env.alternatives:
            if f is env.alternatives[0]:
                assert env.flag is not None
                first, second = env.alternatives
                out += [
                    f"  if ({_value(env, env.flag)}) {{",
                    *_write(env, first, op, "    "),
                    "  } else {",
                    *_write(env, second, op, "    "),
                    "  }",
                ]
        elif f.required:
            out += _write(env, f, op, "  ")
        else:
            out += [f"  if ({_value(env, f)}) {{", *_write(env, f, op, "    "), "  }"]
    return [*out, "  return w.take();", "}"]


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"


def _read_selected(env: Envelope, index: int, op: str) -> list[str]:
    """The read of what the flag selects, when it selects the field at ``index``."""
    f = env.alternatives[index]
    if f.kind == BODY:
        return statement(f"out.{VARIANT} = {_read_body(env, f, op)};", "    ")
    assert env.flag is not None
    state = "true" if index == 0 else "false"
    missing = (
        f"{_article(f.name)} {f.name} {env.what} ({env.flag.name} {state}) without its "
        f"'{f.name}' map"
    )
    return [
        f'    const Object * {f.name} = m.find("{f.name}");',
        f"    if ({f.name} == nullptr) {{",
        *statement(f'fail(where, "{missing}");', "      "),
        "    }",
        *statement(f'out.{VARIANT} = {reader(f)}(*{f.name}, where.key("{f.name}"));', "    "),
    ]


def _read_body(env: Envelope, f: Field, op: str) -> str:
    return (
        f'read_{env.what}_body({op}, body_map(m, "{f.name}"), '
        f"{_body_path(env, f, f'op_name({op})')})"
    )


def _decode(env: Envelope) -> list[str]:
    what = env.what
    params = "const std::uint8_t * data, std::size_t size" + ("" if env.op else ", Op op")
    out = [
        *signature(f"{env.name} decode_{what}", params),
        "{",
        f'  const ParsedMessage parsed(data, size, "{what}");',
        f'  const FieldPath where("{what}");',
        "  const MapReader m(parsed.root(), where);",
        f"  {env.name} out;",
        f'  out.{env.version.name} = read_version(m, "{env.version.name}");',
    ]
    for f in env.fields:
        if f in (env.version, env.body, *env.alternatives):
            continue
        if f is env.op:
            read = f'const Op op = m.required("{f.name}", read_op);'
        elif f is env.flag:
            read = f'const bool {f.name} = m.required("{f.name}", {reader(f)});'
        else:
            how = "required" if f.required else "optional"
            read = f'out.{f.name} = m.{how}("{f.name}", {reader(f)});'
        out += statement(read, "  ")
    if env.flag:
        out += [
            f"  if ({env.flag.name}) {{",
            *_read_selected(env, 0, "op"),
            "  } else {",
            *_read_selected(env, 1, "op"),
            "  }",
        ]
    else:
        out += statement(f"out.{env.body.name} = {_read_body(env, env.body, 'op')};", "  ")
    return [*out, "  return out;", "}"]


def envelopes_cpp() -> str:
    body = [
        "",
        "// The body codec and the runtime it is written on.",
        "using namespace detail;",
        "",
        "namespace",
        "{",
        "",
        "// Room for the envelope and a typical body; text and arrays are added on top of it.",
        f"constexpr std::size_t kSmallMessage = {SMALL_MESSAGE};",
        "",
        "}  // namespace",
    ]
    for env in envelopes():
        body += ["", rule(env.what), "", *_encode(env), "", *_decode(env)]
    return cpp_file(
        'Encode and decode the envelopes (PROTOCOL.md section 13, "Envelopes"), each field as '
        "its kind and the body by the generated body codec; the rules of the version, the op "
        "and the body or error are the runtime's read_version, read_op and body_map "
        "(reader.hpp) and the schema's `selects` and `minimum`.",
        [
            "<cstddef>",
            "<cstdint>",
            "<string_view>",
            '"body_codec.hpp"',
            '"field_path.hpp"',
            '"parse.hpp"',
            '"reader.hpp"',
            '"writer.hpp"',
        ],
        body,
        source_of=f"{INCLUDE}/codec.hpp",
    )


def files() -> dict[str, str]:
    """Path (from the repository root) -> generated text."""
    return {
        f"bridge_plugin/include/{INCLUDE}/messages.hpp": messages_hpp(),
        "bridge_plugin/src/protocol/envelopes.cpp": envelopes_cpp(),
    }
