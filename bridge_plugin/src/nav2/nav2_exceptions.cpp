// Generated from protocol/nav2_pyif_protocol/constants.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Throw the nav2_core exception class an ErrorKind names (constants.py's error names are
// nav2_core's class names); the smoother's in smoother_exceptions.cpp.

#include "nav2_pyif_bridge/nav2_api.hpp"

#include <string>

#include "nav2_pyif_bridge/smoother_exceptions.hpp"

namespace nav2_pyif_bridge
{

void throw_nav2_exception(
  client::PluginKind plugin, client::ErrorKind kind, const std::string & message)
{
#if NAV2_PYIF_JAZZY_API
  using client::ErrorKind;
  if (plugin == client::PluginKind::Smoother) {
    throw_smoother_exception(kind, message);
  }
  switch (kind) {
    case ErrorKind::ControllerException: throw nav2_core::ControllerException(message);
    case ErrorKind::InvalidController: throw nav2_core::InvalidController(message);
    case ErrorKind::ControllerTFError: throw nav2_core::ControllerTFError(message);
    case ErrorKind::FailedToMakeProgress: throw nav2_core::FailedToMakeProgress(message);
    case ErrorKind::PatienceExceeded: throw nav2_core::PatienceExceeded(message);
    case ErrorKind::InvalidPath: throw nav2_core::InvalidPath(message);
    case ErrorKind::NoValidControl: throw nav2_core::NoValidControl(message);
    case ErrorKind::ControllerTimedOut: throw nav2_core::ControllerTimedOut(message);
    case ErrorKind::PlannerException: throw nav2_core::PlannerException(message);
    case ErrorKind::InvalidPlanner: throw nav2_core::InvalidPlanner(message);
    case ErrorKind::StartOccupied: throw nav2_core::StartOccupied(message);
    case ErrorKind::GoalOccupied: throw nav2_core::GoalOccupied(message);
    case ErrorKind::StartOutsideMapBounds: throw nav2_core::StartOutsideMapBounds(message);
    case ErrorKind::GoalOutsideMapBounds: throw nav2_core::GoalOutsideMapBounds(message);
    case ErrorKind::NoValidPathCouldBeFound: throw nav2_core::NoValidPathCouldBeFound(message);
    case ErrorKind::PlannerTimedOut: throw nav2_core::PlannerTimedOut(message);
    case ErrorKind::PlannerTFError: throw nav2_core::PlannerTFError(message);
    case ErrorKind::NoViapointsGiven: throw nav2_core::NoViapointsGiven(message);
    case ErrorKind::PlannerCancelled: throw nav2_core::PlannerCancelled(message);
    default: throw_smoother_exception(kind, message);
  }
#else
  (void)plugin;
  (void)kind;
  throw nav2_core::PlannerException(message);
#endif
}

}  // namespace nav2_pyif_bridge
