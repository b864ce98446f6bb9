// libFuzzer harness: the request envelope and every op's request body (decode_request; the op
// comes from the bytes), then the round trip of whatever decodes. Seeds: protocol/vectors.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.hpp"

namespace protocol = nav2_pyif_bridge::protocol;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  protocol::Request request;
  try {
    request = protocol::decode_request(data, size);
  } catch (const protocol::DecodeError &) {
    return 0;  // refused, as it should be: the host answers BadRequest
  }
  nav2_pyif_bridge::fuzz::expect_round_trip(
    request, [](const protocol::Request & r) {return protocol::encode_request(r);},
    [](const protocol::Bytes & b) {return protocol::decode_request(b);}, "request");
  return 0;
}
