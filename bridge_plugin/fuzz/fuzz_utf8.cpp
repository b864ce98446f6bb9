// libFuzzer harness: the UTF-8 check (utf8.hpp), against a second implementation written
// another way: the Unicode Standard's table of well-formed byte sequences (chapter 3, table
// 3-7), byte range by byte range. The check decodes code points and then refuses overlong
// forms, surrogates and values above U+10FFFF; both must agree on every input.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.hpp"
#include "utf8.hpp"

namespace
{

struct Range
{
  std::uint8_t low;
  std::uint8_t high;
};

// Table 3-7: a lead byte range, then the range of each continuation byte after it.
struct Row
{
  Range lead;
  int extra;
  Range second;
};

constexpr Range kTail{0x80, 0xBF};
constexpr Row kRows[] = {
  {{0xC2, 0xDF}, 1, kTail},
  {{0xE0, 0xE0}, 2, {0xA0, 0xBF}},
  {{0xE1, 0xEC}, 2, kTail},
  {{0xED, 0xED}, 2, {0x80, 0x9F}},
  {{0xEE, 0xEF}, 2, kTail},
  {{0xF0, 0xF0}, 3, {0x90, 0xBF}},
  {{0xF1, 0xF3}, 3, kTail},
  {{0xF4, 0xF4}, 3, {0x80, 0x8F}},
};

bool in(std::uint8_t byte, Range range) {return byte >= range.low && byte <= range.high;}

bool well_formed(const std::uint8_t * s, std::size_t size)
{
  std::size_t i = 0;
  while (i < size) {
    if (s[i] <= 0x7F) {
      ++i;
      continue;
    }
    const Row * row = nullptr;
    for (const Row & candidate : kRows) {
      if (in(s[i], candidate.lead)) {
        row = &candidate;
      }
    }
    if (row == nullptr || size - i <= static_cast<std::size_t>(row->extra) ||
      !in(s[i + 1], row->second))
    {
      return false;
    }
    for (int k = 2; k <= row->extra; ++k) {
      if (!in(s[i + k], kTail)) {
        return false;
      }
    }
    i += row->extra + 1;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  const bool checked = nav2_pyif_bridge::protocol::detail::is_valid_utf8(
    reinterpret_cast<const char *>(data), size);
  if (checked != well_formed(data, size)) {
    nav2_pyif_bridge::fuzz::broken(
      std::string("is_valid_utf8 says ") + (checked ? "valid" : "invalid") +
      ", Unicode's table 3-7 says otherwise");
  }
  return 0;
}
