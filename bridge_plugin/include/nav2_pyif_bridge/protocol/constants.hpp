// Generated from protocol/nav2_pyif_protocol/constants.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Names every party of the protocol shares: the version, the error types and a behaviour's status
// and failure names (PROTOCOL.md sections 3, 7 and 17).

#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace nav2_pyif_bridge::protocol
{

// Sent in every request and reply. Decoders refuse any other value (VersionMismatch).
inline constexpr std::int64_t kProtocolVersion = 2;

// The input names one session may send (a controller's `inputs` parameter): the host
// keeps the latest message of each.
inline constexpr std::size_t kMaxInputs = 64;

// The protocol's own error types (error.type). The nav2_core exception names travel as plain
// strings too; mapping them to exceptions is the plugin's job (client/error_mapping.hpp).
namespace error_type
{
inline constexpr std::string_view kSessionUnknown = "SessionUnknown";
inline constexpr std::string_view kVersionMismatch = "VersionMismatch";
inline constexpr std::string_view kBadRequest = "BadRequest";
inline constexpr std::string_view kUnavailable = "Unavailable";
}  // namespace error_type

// std::nullopt for a name not in `names` (the wire's spelling, by enumerator).
template<class Enum, std::size_t N>
constexpr std::optional<Enum> from_name(
  const std::array<std::string_view, N> & names, std::string_view name) noexcept
{
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == name) {
      return static_cast<Enum>(i);
    }
  }
  return std::nullopt;
}

// TimedBehavior's Status (a behaviour's reply, PROTOCOL.md section 17).
enum class BehaviorStatus : std::uint8_t
{
  Succeeded,
  Failed,
  Running,
};
inline constexpr std::array<std::string_view, 3> kBehaviorStatusNames = {
  "succeeded",
  "failed",
  "running",
};

// Why a behaviour failed: the plugin sets the action result's error code of that name (BackUp's
// COLLISION_AHEAD, Spin's TIMEOUT, ...; UNKNOWN where the action has no such code, and none on
// Humble, whose behaviour results have no error code).
enum class BehaviorFailure : std::uint8_t
{
  None,
  Unknown,
  Timeout,
  TfError,
  InvalidInput,
  CollisionAhead,
};
inline constexpr std::array<std::string_view, 6> kBehaviorFailureNames = {
  "",
  "unknown",
  "timeout",
  "tf_error",
  "invalid_input",
  "collision_ahead",
};

}  // namespace nav2_pyif_bridge::protocol
