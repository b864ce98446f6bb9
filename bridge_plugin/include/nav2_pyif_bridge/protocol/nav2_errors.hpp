// Generated from protocol/nav2_pyif_protocol/constants.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// The plugin types and the nav2_core exceptions each throws (constants.py's ERRORS_BY_PLUGIN,
// GENERIC_ERROR, HOST_FAILURE_ERROR and INVALID_ERROR), as tables the plugin's error mapping
// (client/error_mapping.cpp) looks up.

#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace nav2_pyif_bridge::protocol
{

// The plugin types, as configure's plugin_type names them.
enum class PluginKind : std::uint8_t
{
  Controller,
  GlobalPlanner,
  Smoother,
  GoalChecker,
  ProgressChecker,
  CostmapLayer,
  Behavior,
  PathHandler,
};
inline constexpr std::size_t kPluginKindCount = 8;

// Wire names, by PluginKind.
inline constexpr std::array<std::string_view, kPluginKindCount> kPluginKindNames = {
  "controller",
  "global_planner",
  "smoother",
  "goal_checker",
  "progress_checker",
  "costmap_layer",
  "behavior",
  "path_handler",
};

// The nav2_core exception classes of Jazzy and Kilted, by name; the names are also the wire's
// error.type values (PROTOCOL.md section 7).
enum class ErrorKind : std::uint8_t
{
  ControllerException,
  InvalidController,
  ControllerTFError,
  FailedToMakeProgress,
  PatienceExceeded,
  InvalidPath,
  NoValidControl,
  ControllerTimedOut,
  PlannerException,
  InvalidPlanner,
  StartOccupied,
  GoalOccupied,
  StartOutsideMapBounds,
  GoalOutsideMapBounds,
  NoValidPathCouldBeFound,
  PlannerTimedOut,
  PlannerTFError,
  NoViapointsGiven,
  PlannerCancelled,
  SmootherException,
  InvalidSmoother,
  SmootherTimedOut,
  SmoothedPathInCollision,
  FailedToSmoothPath,
};
inline constexpr std::size_t kErrorKindCount = 24;

// Wire names, by ErrorKind.
inline constexpr std::array<std::string_view, kErrorKindCount> kErrorKindNames = {
  "ControllerException",
  "InvalidController",
  "ControllerTFError",
  "FailedToMakeProgress",
  "PatienceExceeded",
  "InvalidPath",
  "NoValidControl",
  "ControllerTimedOut",
  "PlannerException",
  "InvalidPlanner",
  "StartOccupied",
  "GoalOccupied",
  "StartOutsideMapBounds",
  "GoalOutsideMapBounds",
  "NoValidPathCouldBeFound",
  "PlannerTimedOut",
  "PlannerTFError",
  "NoViapointsGiven",
  "PlannerCancelled",
  "SmootherException",
  "InvalidSmoother",
  "SmootherTimedOut",
  "SmoothedPathInCollision",
  "FailedToSmoothPath",
};

// The plugin type whose exceptions each ErrorKind is one of (InvalidPath: the controller's), by
// ErrorKind.
inline constexpr std::array<PluginKind, kErrorKindCount> kErrorFamily = {
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::Controller,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::GlobalPlanner,
  PluginKind::Smoother,
  PluginKind::Smoother,
  PluginKind::Smoother,
  PluginKind::Smoother,
  PluginKind::Smoother,
};

// The ErrorKinds a plugin of each type (by PluginKind) throws under their own name, bit i for
// ErrorKind i; any other error type becomes the type's generic error.
inline constexpr std::array<std::uint32_t, kPluginKindCount> kOwnErrors = {
  0x000000ffu,  // controller
  0x0007ff00u,  // global_planner
  0x00f80020u,  // smoother
  0x00000001u,  // goal_checker
  0x00000001u,  // progress_checker
  0x00000001u,  // costmap_layer
  0x00000001u,  // behavior
  0x000000ffu,  // path_handler
};

// Each plugin type's catch-all exception, by PluginKind.
inline constexpr std::array<ErrorKind, kPluginKindCount> kGenericError = {
  ErrorKind::ControllerException,
  ErrorKind::PlannerException,
  ErrorKind::SmootherException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
};

// Each plugin type's exception when its host failed it (none alive, no reply in time, Unavailable),
// by PluginKind.
inline constexpr std::array<ErrorKind, kPluginKindCount> kHostFailureError = {
  ErrorKind::NoValidControl,
  ErrorKind::PlannerException,
  ErrorKind::SmootherException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::NoValidControl,
};

// Each plugin type's exception when it cannot be configured, by PluginKind.
inline constexpr std::array<ErrorKind, kPluginKindCount> kInvalidError = {
  ErrorKind::InvalidController,
  ErrorKind::InvalidPlanner,
  ErrorKind::InvalidSmoother,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::ControllerException,
  ErrorKind::InvalidController,
};

template<class Kind>
constexpr std::size_t row_of(Kind kind) noexcept {return static_cast<std::size_t>(kind);}

// The wire's configure.plugin_type of a plugin type.
constexpr std::string_view plugin_type_name(PluginKind kind) noexcept
{
  return kPluginKindNames[row_of(kind)];
}

// The exception's name (also its error.type on the wire).
constexpr std::string_view error_kind_name(ErrorKind kind) noexcept
{
  return kErrorKindNames[row_of(kind)];
}

// The plugin type whose exceptions `kind` is one of (InvalidPath: the controller's).
constexpr PluginKind plugin_kind_of(ErrorKind kind) noexcept
{
  return kErrorFamily[row_of(kind)];
}

// Whether a plugin of type `plugin` throws `kind` under its own name.
constexpr bool belongs_to(ErrorKind kind, PluginKind plugin) noexcept
{
  return (kOwnErrors[row_of(plugin)] >> row_of(kind)) & 1u;
}

// The plugin type's catch-all exception.
constexpr ErrorKind generic_error(PluginKind kind) noexcept
{
  return kGenericError[row_of(kind)];
}

// What a plugin throws when its host, not its planner, failed the call (none alive, no reply in
// time, a broken transport, an Unavailable reply): the class Nav2's recovery conditions retry
// (RELIABILITY.md).
constexpr ErrorKind host_failure_error(PluginKind kind) noexcept
{
  return kHostFailureError[row_of(kind)];
}

// What a plugin throws when it cannot be configured.
constexpr ErrorKind invalid_error(PluginKind kind) noexcept
{
  return kInvalidError[row_of(kind)];
}

// std::nullopt for a name that is no nav2_core exception (protocol errors included).
constexpr std::optional<ErrorKind> error_kind_from_name(std::string_view name) noexcept
{
  for (std::size_t i = 0; i < kErrorKindCount; ++i) {
    if (kErrorKindNames[i] == name) {
      return static_cast<ErrorKind>(i);
    }
  }
  return std::nullopt;
}

}  // namespace nav2_pyif_bridge::protocol
