// Bytes -> messages: the envelopes (PROTOCOL.md section 13, "Envelopes"), read here by hand
// because their fields carry rules of their own (the version first, the op names the body's
// type, either a body or an error); every body and structure is read by the generated
// body_codec.cpp. The envelope is checked before the body, as the Python codec does, so both
// codecs refuse the same messages with the same error types.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <utility>

#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "body_codec.hpp"
#include "field_path.hpp"
#include "reader.hpp"

namespace nav2_pyif_bridge::protocol
{
namespace
{

using detail::FieldPath;
using detail::MapReader;
using detail::Object;
using detail::read_bool;
using detail::read_i64;
using detail::read_str;
using detail::read_u64;

// --- parsing --------------------------------------------------------------------------------

// str and bin objects point into the caller's buffer instead of being copied into the zone:
// the buffer outlives the tree (both live only during one decode call), and the fields are
// copied once, into the message, anyway.
bool reference_input(msgpack::type::object_type, std::size_t, void *)
{
  return true;
}

msgpack::object_handle parse(const std::uint8_t * data, std::size_t size, const char * what)
{
  // Every element takes at least one byte (a map entry two), so no valid message has more
  // elements than bytes; these limits keep a forged length such as "array of 2^32 - 1" from
  // allocating gigabytes before the parser notices the data is short.
  const std::size_t elements = size;
  const msgpack::unpack_limit limit(elements, elements / 2, size, size, size, 64);
  std::size_t offset = 0;
  msgpack::object_handle handle;
  try {
    handle = msgpack::unpack(
      reinterpret_cast<const char *>(data), size, offset, reference_input, nullptr, limit);
  } catch (const std::exception & e) {
    // insufficient_bytes, parse_error, *_size_overflow, depth_size_overflow, ...
    throw DecodeError(error_type::kBadRequest, what, std::string("not valid msgpack: ") + e.what());
  }
  if (offset != size) {
    throw DecodeError(
            error_type::kBadRequest, what,
            "not valid msgpack: " + std::to_string(size - offset) + " extra bytes after the message");
  }
  return handle;
}

// `v` comes first: a message of another version may differ in anything else, so nothing
// else is read before it is known to be ours.
void check_version(const MapReader & message, const char * what)
{
  const Object * v = message.find("v");
  if (v != nullptr && v->type == msgpack::type::POSITIVE_INTEGER &&
    v->via.u64 == static_cast<std::uint64_t>(kProtocolVersion))
  {
    return;
  }
  std::string theirs = "missing";
  if (v != nullptr) {
    theirs = v->type == msgpack::type::POSITIVE_INTEGER ? std::to_string(v->via.u64) :
      v->type == msgpack::type::NEGATIVE_INTEGER ? std::to_string(v->via.i64) :
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
      Object o;
      o.type = msgpack::type::MAP;
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
  const msgpack::object_handle handle = parse(data, size, "request");
  const FieldPath root("request");
  const MapReader m(handle.get(), root);
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
  const msgpack::object_handle handle = parse(data, size, "reply");
  const FieldPath root("reply");
  const MapReader m(handle.get(), root);
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
