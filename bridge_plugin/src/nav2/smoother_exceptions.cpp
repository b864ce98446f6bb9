// nav2_core's smoother exceptions, apart from nav2_exceptions.cpp: smoother_exceptions.hpp and
// controller_exceptions.hpp both define a nav2_core::InvalidPath.
#include "nav2_pyif_bridge/smoother_exceptions.hpp"

#include <string>

#if __has_include(<nav2_core/smoother_exceptions.hpp>)
#  define NAV2_PYIF_HAS_SMOOTHER_EXCEPTIONS 1
#  include "nav2_core/smoother_exceptions.hpp"
#else
#  define NAV2_PYIF_HAS_SMOOTHER_EXCEPTIONS 0
#  include "nav2_core/exceptions.hpp"
#endif

namespace nav2_pyif_bridge
{

void throw_smoother_exception(client::ErrorKind kind, const std::string & message)
{
#if NAV2_PYIF_HAS_SMOOTHER_EXCEPTIONS
  using client::ErrorKind;
  switch (kind) {
    case ErrorKind::InvalidSmoother: throw nav2_core::InvalidSmoother(message);
    case ErrorKind::InvalidPath: throw nav2_core::InvalidPath(message);
    case ErrorKind::SmootherTimedOut: throw nav2_core::SmootherTimedOut(message);
    case ErrorKind::SmoothedPathInCollision: throw nav2_core::SmoothedPathInCollision(message);
    case ErrorKind::FailedToSmoothPath: throw nav2_core::FailedToSmoothPath(message);
    default: throw nav2_core::SmootherException(message);
  }
#else
  (void)kind;  // Humble has no smoother exceptions: smoother_server catches PlannerException
  throw nav2_core::PlannerException(message);
#endif
}

}  // namespace nav2_pyif_bridge
