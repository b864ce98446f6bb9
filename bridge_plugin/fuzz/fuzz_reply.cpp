// libFuzzer harness: the reply envelope and the reply body of every op. A reply does not name
// its op (the plugin knows what it asked), so each input is decoded as the reply to each op in
// turn: every mutation reaches every body decoder, and the seeds (protocol/vectors) need no
// op prefix. Whatever decodes must round-trip.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.hpp"

namespace protocol = nav2_pyif_bridge::protocol;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  for (std::size_t i = 0; i < protocol::kOpCount; ++i) {
    const auto op = static_cast<protocol::Op>(i);
    protocol::Reply reply;
    try {
      reply = protocol::decode_reply(data, size, op);
    } catch (const protocol::DecodeError & error) {
      // Refused, which the plugin maps to a Nav2 exception. A fault in the envelope (its path
      // starts "reply", a body's "<op> reply body") is the same for every op: stop there.
      if (error.field_path().rfind("reply", 0) == 0) {
        return 0;
      }
      continue;
    }
    nav2_pyif_bridge::fuzz::expect_round_trip(
      reply, [](const protocol::Reply & r) {return protocol::encode_reply(r);},
      [op](const protocol::Bytes & b) {return protocol::decode_reply(b, op);}, "reply");
  }
  return 0;
}
