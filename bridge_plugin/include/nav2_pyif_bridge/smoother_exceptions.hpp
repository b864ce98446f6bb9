// nav2_core's smoother exceptions, thrown from a translation unit of their own
// (src/nav2/smoother_exceptions.cpp): smoother_exceptions.hpp and controller_exceptions.hpp both
// define a nav2_core::InvalidPath, so no file may include both. Do not include nav2_api.hpp
// (it includes the controller's) where this is implemented.
#pragma once

#include <string>

#include "nav2_pyif_bridge/client/error_mapping.hpp"

namespace nav2_pyif_bridge
{

// The smoother exception `kind` names (InvalidPath: the smoother's); SmootherException for
// any other kind. Humble has none: PlannerException, which its smoother_server catches.
[[noreturn]] void throw_smoother_exception(client::ErrorKind kind, const std::string & message);

}  // namespace nav2_pyif_bridge
