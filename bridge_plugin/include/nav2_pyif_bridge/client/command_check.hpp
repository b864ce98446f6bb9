// What the plugin checks in a host's ok answer before it reaches Nav2: a command or a plan with a
// NaN or infinite value is never returned (PROTOCOL.md section 7), nor a costmap layer's costs
// for another window. The host checks too; this holds even for a host that does not.
#pragma once

#include <string>

#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/protocol/bodies.hpp"

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

// Throws CallError ControllerException (BadReply) unless the layer's costs are exactly the
// requested window [min_i, max_i) x [min_j, max_j).
void check_window(
  const protocol::UpdateCostsReply & reply, const protocol::UpdateCostsRequest & request,
  const std::string & host);

// The check of an ok reply to `request` from `host`, by its op: a command, a plan, a
// smoothed path, a layer's window (every call's, carried or not: PluginSession).
void check_reply(
  const protocol::RequestBody & request, const protocol::ReplyBody & reply,
  const std::string & host);

}  // namespace nav2_pyif_bridge::client
