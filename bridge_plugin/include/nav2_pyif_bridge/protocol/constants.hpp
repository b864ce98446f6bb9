// Names every party of the protocol shares: the version and the protocol-level error types
// (PROTOCOL.md sections 3 and 7). nav2_core exception names travel as plain strings in
// Error::type; mapping them to exceptions is the plugin's job, not the codec's.
#pragma once

#include <cstdint>
#include <string_view>

namespace nav2_pyif_bridge::protocol
{

// Sent in every request and reply. Decoders refuse any other value (VersionMismatch).
inline constexpr std::int64_t kProtocolVersion = 1;

namespace error_type
{
inline constexpr std::string_view kSessionUnknown = "SessionUnknown";
inline constexpr std::string_view kVersionMismatch = "VersionMismatch";
inline constexpr std::string_view kBadRequest = "BadRequest";
inline constexpr std::string_view kUnavailable = "Unavailable";
}  // namespace error_type

}  // namespace nav2_pyif_bridge::protocol
