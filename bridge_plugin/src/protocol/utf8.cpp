#include "utf8.hpp"

#include <cstdint>

namespace nav2_pyif_bridge::protocol::detail
{

bool is_valid_utf8(const char * data, std::size_t size) noexcept
{
  const auto * s = reinterpret_cast<const unsigned char *>(data);
  std::size_t i = 0;
  while (i < size) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t extra = 0;
    std::uint32_t code = 0;
    std::uint32_t minimum = 0;  // the smallest code point that needs this many bytes
    if ((c & 0xE0) == 0xC0) {
      extra = 1;
      code = c & 0x1Fu;
      minimum = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      extra = 2;
      code = c & 0x0Fu;
      minimum = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      extra = 3;
      code = c & 0x07u;
      minimum = 0x10000;
    } else {
      return false;  // a continuation byte without a lead byte, or 0xF8..0xFF
    }
    if (size - i <= extra) {
      return false;  // truncated sequence
    }
    for (std::size_t k = 1; k <= extra; ++k) {
      const unsigned char next = s[i + k];
      if ((next & 0xC0) != 0x80) {
        return false;
      }
      code = (code << 6) | (next & 0x3Fu);
    }
    if (code < minimum || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
      return false;
    }
    i += extra + 1;
  }
  return true;
}

}  // namespace nav2_pyif_bridge::protocol::detail
