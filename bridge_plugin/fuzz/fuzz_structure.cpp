// libFuzzer harness: the msgpack structure pre-pass (parse.hpp's structure_problem), against
// msgpack-c's own unpacker. The pre-pass is what keeps a forged length from costing gigabytes,
// so it may refuse more than msgpack-c (nesting beyond kMaxNesting) but must never pass bytes
// that msgpack-c then fails on, or stops short of.
#include <msgpack.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_check.hpp"
#include "parse.hpp"

namespace detail = nav2_pyif_bridge::protocol::detail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  const std::string problem = detail::structure_problem(data, size);
  if (!problem.empty()) {
    return 0;
  }
  msgpack_unpacked unpacked;
  msgpack_unpacked_init(&unpacked);
  std::size_t offset = 0;
  const msgpack_unpack_return result =
    msgpack_unpack_next(&unpacked, reinterpret_cast<const char *>(data), size, &offset);
  msgpack_unpacked_destroy(&unpacked);
  if (result != MSGPACK_UNPACK_SUCCESS) {
    nav2_pyif_bridge::fuzz::broken(
      "the pre-pass passed bytes msgpack-c cannot unpack (" + std::to_string(result) + ")");
  }
  if (offset != size) {
    nav2_pyif_bridge::fuzz::broken(
      "the pre-pass passed one value of " + std::to_string(size) + " bytes, msgpack-c read " +
      std::to_string(offset));
  }
  return 0;
}
