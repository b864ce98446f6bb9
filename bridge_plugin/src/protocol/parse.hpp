// Bytes -> msgpack-c's object tree, for the envelope and body readers (reader.hpp).
#pragma once

#include <msgpack.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace nav2_pyif_bridge::protocol::detail
{

// msgpack-c's unpacker keeps its open arrays and maps on a fixed stack of this many levels
// (MSGPACK_EMBED_STACK_SIZE); a message nests a handful.
constexpr std::size_t kMaxNesting = 32;

// What is wrong with `data` as exactly one msgpack value, or "" when nothing is: read header
// by header without building anything, so every declared length is checked against the bytes
// that remain *before* msgpack-c allocates for it. msgpack_unpack_next allocates an array's or
// a map's elements as soon as it reads their count, so a forged "array of 2^32 - 1" would
// otherwise cost ~100 GB before the parser noticed that the data is short.
std::string structure_problem(const std::uint8_t * data, std::size_t size);

// One message, parsed. str and bin objects point into the caller's buffer (msgpack-c copies
// no payload), which must outlive this; arrays and maps live in the tree's own zone.
class ParsedMessage
{
public:
  // Throws DecodeError (BadRequest) naming `what` ("request", "reply") unless `data` is
  // exactly one well-formed msgpack value.
  ParsedMessage(const std::uint8_t * data, std::size_t size, const char * what);
  ~ParsedMessage();
  ParsedMessage(const ParsedMessage &) = delete;
  ParsedMessage & operator=(const ParsedMessage &) = delete;

  const msgpack_object & root() const noexcept {return unpacked_.data;}

private:
  msgpack_unpacked unpacked_{};
};

}  // namespace nav2_pyif_bridge::protocol::detail
