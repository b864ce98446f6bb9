// Which Nav2 this package is built against, detected at build time: Jazzy and Kilted have
// nav2_core/controller_exceptions.hpp (and with it Controller::cancel/reset and the planner's
// cancel checker); Humble has only nav2_core/exceptions.hpp (PlannerException). CMake sets
// NAV2_PYIF_JAZZY_API after check_include_file_cxx; __has_include decides otherwise.
#pragma once

#include "nav2_pyif_bridge/client/error_mapping.hpp"

#ifndef NAV2_PYIF_JAZZY_API
#  if __has_include(<nav2_core/controller_exceptions.hpp>)
#    define NAV2_PYIF_JAZZY_API 1
#  else
#    define NAV2_PYIF_JAZZY_API 0
#  endif
#endif

#if NAV2_PYIF_JAZZY_API
#  include "nav2_core/controller_exceptions.hpp"
#  include "nav2_core/planner_exceptions.hpp"
#else
#  include "nav2_core/exceptions.hpp"
#endif

namespace nav2_pyif_bridge
{

inline constexpr client::Nav2Api kNav2Api =
  NAV2_PYIF_JAZZY_API ? client::Nav2Api::Jazzy : client::Nav2Api::Humble;

// Throw the nav2_core exception class `kind` names on this distribution (Humble:
// PlannerException for everything), with `message`. `plugin` picks between nav2_core's two
// InvalidPath classes (the controller's and the smoother's).
[[noreturn]] void throw_nav2_exception(
  client::PluginKind plugin, client::ErrorKind kind, const std::string & message);

}  // namespace nav2_pyif_bridge
