// A bin whose byte count follows from other fields (a costmap's data: size_x * size_y bytes),
// checked alike by the encoder (writer.cpp) and the decoder (reader.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>

namespace nav2_pyif_bridge::protocol::detail
{

// "" when `bytes` is the product of `sizes`, else e.g. "12 bytes, but size 5 x 3 needs 15".
inline std::string cells_problem(std::size_t bytes, std::initializer_list<std::uint64_t> sizes)
{
  std::uint64_t needed = 1;
  std::string size_text;
  for (const std::uint64_t size : sizes) {
    needed *= size;
    size_text += (size_text.empty() ? "" : " x ") + std::to_string(size);
  }
  if (bytes == needed) {
    return "";
  }
  return std::to_string(bytes) + " bytes, but size " + size_text + " needs " +
         std::to_string(needed);
}

}  // namespace nav2_pyif_bridge::protocol::detail
