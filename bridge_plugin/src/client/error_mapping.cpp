#include "nav2_pyif_bridge/client/error_mapping.hpp"

#include "nav2_pyif_bridge/protocol/constants.hpp"

namespace nav2_pyif_bridge::client
{

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
