#include "nav2_pyif_bridge/client/error_mapping.hpp"

#include <array>

namespace nav2_pyif_bridge::client
{
namespace
{

constexpr std::array<std::string_view, kErrorKindCount> kNames = {
  "ControllerException", "InvalidController", "ControllerTFError", "FailedToMakeProgress",
  "PatienceExceeded", "InvalidPath", "NoValidControl", "ControllerTimedOut",
  "PlannerException", "InvalidPlanner", "StartOccupied", "GoalOccupied",
  "StartOutsideMapBounds", "GoalOutsideMapBounds", "NoValidPathCouldBeFound",
  "PlannerTimedOut", "PlannerTFError", "NoViapointsGiven", "PlannerCancelled",
  "SmootherException", "InvalidSmoother", "SmootherTimedOut", "SmoothedPathInCollision",
  "FailedToSmoothPath",
};
static_assert(static_cast<std::size_t>(ErrorKind::FailedToSmoothPath) + 1 == kErrorKindCount);

}  // namespace

std::string_view plugin_type_name(PluginKind kind) noexcept
{
  switch (kind) {
    case PluginKind::Controller: return "controller";
    case PluginKind::GlobalPlanner: return "global_planner";
    case PluginKind::Smoother: return "smoother";
    case PluginKind::GoalChecker: return "goal_checker";
    case PluginKind::ProgressChecker: return "progress_checker";
    case PluginKind::CostmapLayer: return "costmap_layer";
  }
  return "controller";
}

std::string_view error_kind_name(ErrorKind kind) noexcept
{
  return kNames[static_cast<std::size_t>(kind)];
}

std::optional<ErrorKind> error_kind_from_name(std::string_view name) noexcept
{
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (kNames[i] == name) {
      return static_cast<ErrorKind>(i);
    }
  }
  return std::nullopt;
}

PluginKind plugin_kind_of(ErrorKind kind) noexcept
{
  if (kind < ErrorKind::PlannerException) {
    return PluginKind::Controller;
  }
  return kind < ErrorKind::SmootherException ? PluginKind::GlobalPlanner : PluginKind::Smoother;
}

bool belongs_to(ErrorKind kind, PluginKind plugin) noexcept
{
  switch (plugin) {
    case PluginKind::Controller:
    case PluginKind::GlobalPlanner:
      return plugin_kind_of(kind) == plugin;
    case PluginKind::Smoother:
      return kind == ErrorKind::InvalidPath || plugin_kind_of(kind) == PluginKind::Smoother;
    case PluginKind::GoalChecker:
    case PluginKind::ProgressChecker:
    case PluginKind::CostmapLayer:
      return kind == ErrorKind::ControllerException;
  }
  return false;
}

ErrorKind generic_error(PluginKind kind) noexcept
{
  switch (kind) {
    case PluginKind::GlobalPlanner: return ErrorKind::PlannerException;
    case PluginKind::Smoother: return ErrorKind::SmootherException;
    default: return ErrorKind::ControllerException;
  }
}

ErrorKind timed_out_error(PluginKind kind) noexcept
{
  switch (kind) {
    case PluginKind::GlobalPlanner: return ErrorKind::PlannerTimedOut;
    case PluginKind::Smoother: return ErrorKind::SmootherTimedOut;
    default: return ErrorKind::ControllerTimedOut;
  }
}

ErrorKind invalid_error(PluginKind kind) noexcept
{
  switch (kind) {
    case PluginKind::Controller: return ErrorKind::InvalidController;
    case PluginKind::GlobalPlanner: return ErrorKind::InvalidPlanner;
    case PluginKind::Smoother: return ErrorKind::InvalidSmoother;
    default: return ErrorKind::ControllerException;
  }
}

ErrorKind for_api(ErrorKind kind, Nav2Api api) noexcept
{
  return api == Nav2Api::Humble ? ErrorKind::PlannerException : kind;
}

CallError::CallError(ErrorKind kind, Cause cause, const std::string & message, Remote remote)
: std::runtime_error(message), kind_(kind), cause_(cause), remote_(std::move(remote))
{
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
  return CallError(
    generic_error(kind), Cause::Remote, "[" + error.type + "] " + error.message,
    std::move(remote));
}

}  // namespace nav2_pyif_bridge::client
