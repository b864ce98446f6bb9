// Bytes -> messages: the envelopes (PROTOCOL.md section 13, "Envelopes"), read here by hand
// because their fields carry rules of their own (the version first, the op names the body's
// type, either a body or an error); every body and structure is read by the generated
// body_codec.cpp. The envelope is checked before the body, as the Python codec does, so both
// codecs refuse the same messages with the same error types.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "body_codec.hpp"
#include "field_path.hpp"
#include "parse.hpp"
#include "reader.hpp"

namespace nav2_pyif_bridge::protocol
{
namespace
{

using detail::FieldPath;
using detail::MapReader;
using detail::Object;
using detail::ParsedMessage;
using detail::read_bool;
using detail::read_i64;
using detail::read_str;
using detail::read_u64;

// `v` comes first: a message of another version may differ in anything else, so nothing
// else is read before it is known to be ours.
void check_version(const MapReader & message, const char * what)
{
  const Object * v = message.find("v");
  if (v != nullptr && v->type == MSGPACK_OBJECT_POSITIVE_INTEGER &&
    v->via.u64 == static_cast<std::uint64_t>(kProtocolVersion))
  {
    return;
  }
  std::string theirs = "missing";
  if (v != nullptr) {
    theirs = v->type == MSGPACK_OBJECT_POSITIVE_INTEGER ? std::to_string(v->via.u64) :
      v->type == MSGPACK_OBJECT_NEGATIVE_INTEGER ? std::to_string(v->via.i64) :
      std::string("of type ") + detail::type_name(*v);
  }
  throw DecodeError(
          error_type::kVersionMismatch, std::string(what) + ".v",
          std::string(what) + " speaks protocol version " + theirs + "; this codec speaks " +
          std::to_string(kProtocolVersion));
}

// The body map, or an empty one when absent: the Python codec reads a missing body as {}.
const Object & body_of(const MapReader & message)
{
  static const Object empty_map = [] {
      Object o{};
      o.type = MSGPACK_OBJECT_MAP;
      o.via.map.size = 0;
      o.via.map.ptr = nullptr;
      return o;
    }();
  const Object * body = message.find("body");
  return body != nullptr ? *body : empty_map;
}

std::string known_ops()
{
  std::string out;
  for (const auto name : kOpNames) {
    out.append(out.empty() ? "" : ", ").append(name);
  }
  return out;
}

}  // namespace

// --- envelopes ------------------------------------------------------------------------------

Request decode_request(const std::uint8_t * data, std::size_t size)
{
  const ParsedMessage parsed(data, size, "request");
  const FieldPath root("request");
  const MapReader m(parsed.root(), root);
  check_version(m, "request");

  Request out;
  const std::string op_text = m.required("op", read_str);
  const auto op = op_from_name(op_text);
  if (!op) {
    detail::fail(root.key("op"), "unknown op '" + op_text + "'; known: " + known_ops());
  }
  out.sid = m.required("sid", read_str);
  out.epoch = m.required("epoch", read_u64);
  if (out.epoch < 1) {
    detail::fail(root.key("epoch"), "expected an int >= 1, got 0");
  }
  out.seq = m.required("seq", read_u64);
  out.body =
    detail::read_request_body(*op, body_of(m), FieldPath(op_name(*op), " request body"));
  return out;
}

Reply decode_reply(const std::uint8_t * data, std::size_t size, Op op)
{
  const ParsedMessage parsed(data, size, "reply");
  const FieldPath root("reply");
  const MapReader m(parsed.root(), root);
  check_version(m, "reply");

  Reply out;
  out.seq = m.required("seq", read_u64);
  const bool ok = m.required("ok", read_bool);
  out.host = m.required("host", read_str);
  out.compute_ns = m.required("compute_ns", read_i64);
  if (ok) {
    out.outcome =
      detail::read_reply_body(op, body_of(m), FieldPath(op_name(op), " reply body"));
  } else {
    const Object * error = m.find("error");
    if (error == nullptr) {
      detail::fail(root, "an error reply (ok false) without its 'error' map");
    }
    out.outcome = detail::read_error(*error, root.key("error"));
  }
  return out;
}

}  // namespace nav2_pyif_bridge::protocol
