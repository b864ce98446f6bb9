// Encode and decode requests and replies in the canonical form of PROTOCOL.md section 2:
// map keys in schema order, optional fields left out when absent, floats always float64,
// ints in their shortest form, text as str, byte arrays as bin. Identical messages give
// identical bytes in this codec and in the Python one (checked against protocol/vectors).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "nav2_pyif_bridge/protocol/errors.hpp"
#include "nav2_pyif_bridge/protocol/messages.hpp"
#include "nav2_pyif_bridge/protocol/ops.hpp"

namespace nav2_pyif_bridge::protocol
{

using Bytes = std::vector<std::uint8_t>;

// Throw EncodeError for messages that break the schema (see errors.hpp).
Bytes encode_request(const Request & request);
Bytes encode_reply(const Reply & reply);

// Throw DecodeError. Decoders accept an int where a float is specified, treat nil like an
// absent field and ignore keys they do not know (forward compatibility), like the Python
// codec. A `v` other than kProtocolVersion is a DecodeError of type VersionMismatch.
Request decode_request(const std::uint8_t * data, std::size_t size);
inline Request decode_request(const Bytes & data)
{
  return decode_request(data.data(), data.size());
}

// A reply does not carry its op: the caller says which op it asked, which picks the body type.
Reply decode_reply(const std::uint8_t * data, std::size_t size, Op op);
inline Reply decode_reply(const Bytes & data, Op op)
{
  return decode_reply(data.data(), data.size(), op);
}

}  // namespace nav2_pyif_bridge::protocol
