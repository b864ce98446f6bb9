// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Names every party of the protocol shares: the version and the error types (PROTOCOL.md sections 3
// and 7).

#pragma once

#include <cstdint>
#include <string_view>

namespace nav2_pyif_bridge::protocol
{

// Sent in every request and reply. Decoders refuse any other value (VersionMismatch).
inline constexpr std::int64_t kProtocolVersion = 2;

// The protocol's own error types (error.type). The nav2_core exception names travel as plain
// strings too; mapping them to exceptions is the plugin's job (client/error_mapping.hpp).
namespace error_type
{
inline constexpr std::string_view kSessionUnknown = "SessionUnknown";
inline constexpr std::string_view kVersionMismatch = "VersionMismatch";
inline constexpr std::string_view kBadRequest = "BadRequest";
inline constexpr std::string_view kUnavailable = "Unavailable";
}  // namespace error_type

}  // namespace nav2_pyif_bridge::protocol
