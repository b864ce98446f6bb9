#include "nav2_pyif_bridge/client/error_mapping.hpp"

#include <cstddef>

#include "nav2_pyif_bridge/protocol/constants.hpp"

namespace nav2_pyif_bridge::client
{
namespace
{

constexpr std::size_t index(PluginKind kind) noexcept {return static_cast<std::size_t>(kind);}
constexpr std::size_t index(ErrorKind kind) noexcept {return static_cast<std::size_t>(kind);}

}  // namespace

std::string_view plugin_type_name(PluginKind kind) noexcept
{
  return protocol::kPluginKindNames[index(kind)];
}

std::string_view error_kind_name(ErrorKind kind) noexcept
{
  return protocol::kErrorKindNames[index(kind)];
}

std::optional<ErrorKind> error_kind_from_name(std::string_view name) noexcept
{
  for (std::size_t i = 0; i < kErrorKindCount; ++i) {
    if (protocol::kErrorKindNames[i] == name) {
      return static_cast<ErrorKind>(i);
    }
  }
  return std::nullopt;
}

PluginKind plugin_kind_of(ErrorKind kind) noexcept
{
  return protocol::kErrorFamily[index(kind)];
}

bool belongs_to(ErrorKind kind, PluginKind plugin) noexcept
{
  return (protocol::kOwnErrors[index(plugin)] >> index(kind)) & 1u;
}

ErrorKind generic_error(PluginKind kind) noexcept
{
  return protocol::kGenericError[index(kind)];
}

ErrorKind host_failure_error(PluginKind kind) noexcept
{
  return protocol::kHostFailureError[index(kind)];
}

ErrorKind invalid_error(PluginKind kind) noexcept
{
  return protocol::kInvalidError[index(kind)];
}

ErrorKind for_api(ErrorKind kind, Nav2Api api) noexcept
{
  return api == Nav2Api::Humble ? ErrorKind::PlannerException : kind;
}

CallError::CallError(ErrorKind kind, Cause cause, const std::string & message, Remote remote)
: std::runtime_error(message), kind_(kind), cause_(cause), remote_(std::move(remote))
{
}

bool CallError::host_failed() const noexcept
{
  return unreachable() ||
         (cause_ == Cause::Remote && remote_.type == protocol::error_type::kUnavailable);
}

std::string CallError::log_text() const
{
  std::string text = what();
  if (!remote_.python_type.empty()) {
    text += " (" + remote_.python_type + ")";
  }
  if (!remote_.traceback.empty()) {
    text += "\nPython traceback from the planner host:\n" + remote_.traceback;
    if (text.back() == '\n') {
      text.pop_back();
    }
  }
  return text;
}

CallError error_from_reply(const protocol::Error & error, PluginKind kind)
{
  CallError::Remote remote{error.type, error.traceback, error.python_type};
  const std::optional<ErrorKind> named = error_kind_from_name(error.type);
  if (named && belongs_to(*named, kind)) {
    return CallError(*named, Cause::Remote, error.message, std::move(remote));
  }
  if (error.type == protocol::error_type::kUnavailable) {
    return CallError(
      host_failure_error(kind), Cause::Remote, "[" + error.type + "] " + error.message,
      std::move(remote));
  }
  return CallError(
    generic_error(kind), Cause::Remote, "[" + error.type + "] " + error.message,
    std::move(remote));
}

}  // namespace nav2_pyif_bridge::client
