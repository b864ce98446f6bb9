// Generated from protocol/nav2_pyif_protocol/constants.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Throw nav2_core's smoother exceptions (smoother_exceptions.hpp), apart from nav2_exceptions.cpp:
// nav2_core's smoother and controller headers both define an InvalidPath.

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
    case ErrorKind::InvalidPath: throw nav2_core::InvalidPath(message);
    case ErrorKind::InvalidSmoother: throw nav2_core::InvalidSmoother(message);
    case ErrorKind::SmootherTimedOut: throw nav2_core::SmootherTimedOut(message);
    case ErrorKind::SmoothedPathInCollision: throw nav2_core::SmoothedPathInCollision(message);
    case ErrorKind::FailedToSmoothPath: throw nav2_core::FailedToSmoothPath(message);
    default: throw nav2_core::SmootherException(message);
  }
#else
  // Humble has no smoother exceptions: its smoother_server catches PlannerException
  (void)kind;
  throw nav2_core::PlannerException(message);
#endif
}

}  // namespace nav2_pyif_bridge
