// What the plugin checks in a host's answer before it reaches Nav2: a command or a plan with a
// NaN or infinite value is never returned (PROTOCOL.md section 7). The host checks too; this
// holds even for a host that does not.
#pragma once

#include <string>

#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::client
{

// The names of the non-finite components ("vx=nan, wz=inf"), empty when all are finite.
std::string non_finite_components(const protocol::TwistStamped & cmd);

// Throws CallError NoValidControl naming the non-finite components and the host.
void check_command(const protocol::TwistStamped & cmd, const std::string & host);

// Throws CallError `kind` (NoValidPathCouldBeFound for a plan, FailedToSmoothPath for a
// smoothed path) naming `what` (the reply), the first non-finite pose and the host.
void check_path(
  const protocol::Path & path, const std::string & host,
  ErrorKind kind = ErrorKind::NoValidPathCouldBeFound, const char * what = "create_plan reply");

}  // namespace nav2_pyif_bridge::client
