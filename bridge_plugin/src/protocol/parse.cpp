#include "parse.hpp"

#include <vector>

#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "nav2_pyif_bridge/protocol/errors.hpp"

namespace nav2_pyif_bridge::protocol::detail
{
namespace
{

const char * const kShort = "insufficient bytes";

// One header: the bytes after it that belong to the value (str/bin/ext payloads, numbers)
// and the elements it opens (an array's items, a map's keys and values).
struct Header
{
  std::uint64_t payload = 0;
  std::uint64_t elements = 0;
  bool container = false;
};

// A big-endian length field of `width` bytes at data[pos]; false when the data ends first.
bool read_length(
  const std::uint8_t * data, std::size_t size, std::size_t & pos, std::size_t width,
  std::uint64_t & out)
{
  if (size - pos < width) {
    return false;
  }
  out = 0;
  for (std::size_t i = 0; i < width; ++i) {
    out = (out << 8) | data[pos + i];
  }
  pos += width;
  return true;
}

// Reads the header at data[pos] (moving pos past it); "" or the problem.
std::string read_header(
  const std::uint8_t * data, std::size_t size, std::size_t & pos, Header & h)
{
  const std::uint8_t b = data[pos++];
  std::uint64_t n = 0;
  // The spec's format table (msgpack/spec.md "Formats").
  if (b <= 0x7f || b >= 0xe0 || b == 0xc0 || b == 0xc2 || b == 0xc3) {
    return "";  // fixint, negative fixint, nil, false, true
  }
  if (b <= 0x8f) {
    h = {0, 2u * (b & 0x0fu), true};
    return "";
  }
  if (b <= 0x9f) {
    h = {0, b & 0x0fu, true};
    return "";
  }
  if (b <= 0xbf) {
    h.payload = b & 0x1fu;
    return "";
  }
  switch (b) {
    case 0xc4: case 0xd9:  // bin 8, str 8
      if (!read_length(data, size, pos, 1, n)) {return kShort;}
      h.payload = n;
      return "";
    case 0xc5: case 0xda:  // bin 16, str 16
      if (!read_length(data, size, pos, 2, n)) {return kShort;}
      h.payload = n;
      return "";
    case 0xc6: case 0xdb:  // bin 32, str 32
      if (!read_length(data, size, pos, 4, n)) {return kShort;}
      h.payload = n;
      return "";
    case 0xc7: case 0xc8: case 0xc9:  // ext 8/16/32: the length, then a type byte
      if (!read_length(data, size, pos, std::size_t{1} << (b - 0xc7), n)) {return kShort;}
      h.payload = n + 1;
      return "";
    case 0xca: case 0xcb:  // float 32/64
      h.payload = b == 0xca ? 4 : 8;
      return "";
    case 0xcc: case 0xcd: case 0xce: case 0xcf:  // uint 8/16/32/64
      h.payload = std::uint64_t{1} << (b - 0xcc);
      return "";
    case 0xd0: case 0xd1: case 0xd2: case 0xd3:  // int 8/16/32/64
      h.payload = std::uint64_t{1} << (b - 0xd0);
      return "";
    case 0xd4: case 0xd5: case 0xd6: case 0xd7: case 0xd8:  // fixext 1..16: type + data
      h.payload = 1 + (std::uint64_t{1} << (b - 0xd4));
      return "";
    case 0xdc: case 0xdd:  // array 16/32
      if (!read_length(data, size, pos, b == 0xdc ? 2 : 4, n)) {return kShort;}
      h = {0, n, true};
      return "";
    case 0xde: case 0xdf:  // map 16/32
      if (!read_length(data, size, pos, b == 0xde ? 2 : 4, n)) {return kShort;}
      h = {0, 2 * n, true};
      return "";
    default:  // 0xc1, which the spec never uses
      return "parse error: byte 0xc1 at offset " + std::to_string(pos - 1) +
             " is no msgpack type";
  }
}

}  // namespace

std::string structure_problem(const std::uint8_t * data, std::size_t size)
{
  std::vector<std::uint64_t> open;  // per open array or map: the elements it has left
  std::uint64_t pending = 1;        // the elements left to read, all levels together
  std::size_t pos = 0;
  while (pending > 0) {
    if (pos >= size) {
      return kShort;
    }
    Header h;
    const std::string problem = read_header(data, size, pos, h);
    if (!problem.empty()) {
      return problem;
    }
    if (h.payload > size - pos) {
      return kShort;
    }
    pos += h.payload;
    --pending;
    if (!open.empty()) {
      --open.back();
    }
    if (h.container) {
      if (open.size() >= kMaxNesting) {
        return "arrays and maps nested deeper than " + std::to_string(kMaxNesting) + " levels";
      }
      // Every element takes at least one byte, so a count beyond the bytes left is forged
      // (or cut short); refusing it here is what keeps msgpack-c from allocating it.
      if (pending + h.elements > size - pos) {
        return std::string(kShort) + ": " + std::to_string(h.elements) +
               " elements declared with " + std::to_string(size - pos) + " bytes left";
      }
      pending += h.elements;
      open.push_back(h.elements);
    }
    while (!open.empty() && open.back() == 0) {
      open.pop_back();
    }
  }
  if (pos != size) {
    return std::to_string(size - pos) + " extra bytes after the message";
  }
  return "";
}

ParsedMessage::ParsedMessage(const std::uint8_t * data, std::size_t size, const char * what)
{
  const std::string problem = structure_problem(data, size);
  if (!problem.empty()) {
    throw DecodeError(error_type::kBadRequest, what, "not valid msgpack: " + problem);
  }
  msgpack_unpacked_init(&unpacked_);
  std::size_t offset = 0;
  const msgpack_unpack_return result =
    msgpack_unpack_next(&unpacked_, reinterpret_cast<const char *>(data), size, &offset);
  if (result != MSGPACK_UNPACK_SUCCESS || offset != size) {
    // Not reached for what structure_problem accepts, unless memory runs out.
    msgpack_unpacked_destroy(&unpacked_);
    throw DecodeError(
            error_type::kBadRequest, what,
            "not valid msgpack: msgpack-c's unpacker failed (" + std::to_string(result) + ")");
  }
}

ParsedMessage::~ParsedMessage()
{
  msgpack_unpacked_destroy(&unpacked_);
}

}  // namespace nav2_pyif_bridge::protocol::detail
