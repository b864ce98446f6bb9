// Messages -> canonical bytes: the envelopes (PROTOCOL.md section 13, "Envelopes"), written
// here by hand because their fields carry rules of their own (the op follows from the body's
// type; a reply has either a body or an error). Every body and structure is written by the
// generated body_codec.cpp.
#include <cstddef>
#include <string_view>
#include <variant>

#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "body_codec.hpp"
#include "field_path.hpp"
#include "writer.hpp"

namespace nav2_pyif_bridge::protocol
{
namespace
{

using detail::FieldPath;
using detail::Writer;

// Room for the envelope and a typical body; text and arrays are added on top of it.
constexpr std::size_t kSmallMessage = 512;

}  // namespace

Bytes encode_request(const Request & request)
{
  const std::string_view op = op_name(request.op());
  const FieldPath root("request");
  Writer w(kSmallMessage + detail::payload_size(request.body));
  w.map(6);
  w.key("v");
  w.i64(request.v);
  w.key("op");
  w.key(op);
  w.key("sid");
  w.str(request.sid, root.key("sid"));
  w.key("epoch");
  w.u64(request.epoch);
  w.key("seq");
  w.u64(request.seq);
  w.key("body");
  detail::write(w, request.body, FieldPath(op, " request body"));
  return w.take();
}

Bytes encode_reply(const Reply & reply)
{
  const FieldPath root("reply");
  Writer w(
    kSmallMessage +
    (reply.ok() ? detail::payload_size(reply.body()) : detail::payload_size(reply.error())));
  w.map(6);
  w.key("v");
  w.i64(reply.v);
  w.key("seq");
  w.u64(reply.seq);
  w.key("ok");
  w.boolean(reply.ok());
  if (reply.ok()) {
    w.key("body");
    detail::write(w, reply.body(), FieldPath(op_name(op_of(reply.body())), " reply body"));
  } else {
    w.key("error");
    detail::write(w, reply.error(), root.key("error"));
  }
  w.key("host");
  w.str(reply.host, root.key("host"));
  w.key("compute_ns");
  w.i64(reply.compute_ns);
  return w.take();
}

}  // namespace nav2_pyif_bridge::protocol
