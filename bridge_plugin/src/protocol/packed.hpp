// Packed float64 arrays (paths, footprints): little-endian on the wire whatever the host's
// byte order, so the bytes are assembled explicitly instead of memcpy'd.
#pragma once

#include <cstdint>
#include <cstring>

namespace nav2_pyif_bridge::protocol::detail
{

inline void store_f64_le(double value, std::uint8_t * out) noexcept
{
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  for (int i = 0; i < 8; ++i) {
    out[i] = static_cast<std::uint8_t>(bits >> (8 * i));
  }
}

inline double load_f64_le(const std::uint8_t * in) noexcept
{
  std::uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) {
    bits |= static_cast<std::uint64_t>(in[i]) << (8 * i);
  }
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace nav2_pyif_bridge::protocol::detail
