// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Encode and decode the envelopes (PROTOCOL.md section 13, "Envelopes"), each field as its kind and
// the body by the generated body codec; the rules of the version, the op and the body or error are
// the runtime's read_version, read_op and body_map (reader.hpp) and the schema's `selects` and
// `minimum`.

#include "nav2_pyif_bridge/protocol/codec.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "body_codec.hpp"
#include "field_path.hpp"
#include "parse.hpp"
#include "reader.hpp"
#include "writer.hpp"

namespace nav2_pyif_bridge::protocol
{

// The body codec and the runtime it is written on.
using namespace detail;

namespace
{

// Room for the envelope and a typical body; text and arrays are added on top of it.
constexpr std::size_t kSmallMessage = 512;

}  // namespace

// --- request -------------------------------------------------------------------------------------

Bytes encode_request(const Request & request)
{
  const std::string_view op = op_name(request.op());
  const FieldPath where("request");
  Writer w(kSmallMessage + request.sid.size() + payload_size(request.body));
  w.map(6);
  w.key("v");
  w.i64(request.v);
  w.key("op");
  w.key(op);
  w.key("sid");
  w.str(request.sid, where.key("sid"));
  w.key("epoch");
  w.u64(request.epoch);
  w.key("seq");
  w.u64(request.seq);
  w.key("body");
  write(w, request.body, FieldPath(op, " request body"));
  return w.take();
}

Request decode_request(const std::uint8_t * data, std::size_t size)
{
  const ParsedMessage parsed(data, size, "request");
  const FieldPath where("request");
  const MapReader m(parsed.root(), where);
  Request out;
  out.v = read_version(m, "v");
  const Op op = m.required("op", read_op);
  out.sid = m.required("sid", read_str);
  out.epoch = m.required("epoch", read_at_least<read_u64, 1>);
  out.seq = m.required("seq", read_u64);
  out.body = read_request_body(op, body_map(m, "body"), FieldPath(op_name(op), " request body"));
  return out;
}

// --- reply ---------------------------------------------------------------------------------------

Bytes encode_reply(const Reply & reply)
{
  const FieldPath where("reply");
  Writer w(kSmallMessage + reply.host.size()
      + (reply.ok() ? payload_size(reply.body()) : payload_size(reply.error())));
  w.map(6);
  w.key("v");
  w.i64(reply.v);
  w.key("seq");
  w.u64(reply.seq);
  w.key("ok");
  w.boolean(reply.ok());
  if (reply.ok()) {
    w.key("body");
    write(w, reply.body(), FieldPath(op_name(op_of(reply.body())), " reply body"));
  } else {
    w.key("error");
    write(w, reply.error(), where.key("error"));
  }
  w.key("host");
  w.str(reply.host, where.key("host"));
  w.key("compute_ns");
  w.i64(reply.compute_ns);
  return w.take();
}

Reply decode_reply(const std::uint8_t * data, std::size_t size, Op op)
{
  const ParsedMessage parsed(data, size, "reply");
  const FieldPath where("reply");
  const MapReader m(parsed.root(), where);
  Reply out;
  out.v = read_version(m, "v");
  out.seq = m.required("seq", read_u64);
  const bool ok = m.required("ok", read_bool);
  out.host = m.required("host", read_str);
  out.compute_ns = m.required("compute_ns", read_i64);
  if (ok) {
    out.outcome = read_reply_body(op, body_map(m, "body"), FieldPath(op_name(op), " reply body"));
  } else {
    const Object * error = m.find("error");
    if (error == nullptr) {
      fail(where, "an error reply (ok false) without its 'error' map");
    }
    out.outcome = read_error(*error, where.key("error"));
  }
  return out;
}

}  // namespace nav2_pyif_bridge::protocol
