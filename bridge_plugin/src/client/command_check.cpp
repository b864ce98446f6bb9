#include "nav2_pyif_bridge/client/command_check.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <sstream>
#include <string_view>
#include <variant>

#include "nav2_pyif_bridge/client/error_mapping.hpp"

namespace nav2_pyif_bridge::client
{
namespace
{

constexpr std::array<std::string_view, 6> kTwistNames = {"vx", "vy", "vz", "wx", "wy", "wz"};

std::string describe(double value)
{
  if (std::isnan(value)) {
    return "nan";
  }
  return value > 0 ? "inf" : "-inf";
}

std::string host_part(const std::string & host)
{
  return host.empty() ? std::string() : " from host " + host;
}

}  // namespace

std::string non_finite_components(const protocol::TwistStamped & cmd)
{
  std::string out;
  for (std::size_t i = 0; i < cmd.twist.size(); ++i) {
    if (!std::isfinite(cmd.twist[i])) {
      out += (out.empty() ? "" : ", ") + std::string(kTwistNames[i]) + "=" +
        describe(cmd.twist[i]);
    }
  }
  return out;
}

void check_command(const protocol::TwistStamped & cmd, const std::string & host)
{
  const std::string bad = non_finite_components(cmd);
  if (!bad.empty()) {
    throw CallError(
            ErrorKind::NoValidControl, Cause::Local,
            "compute_velocity_commands reply" + host_part(host) +
            " has non-finite components: " + bad + "; no command returned");
  }
}

void check_path(
  const protocol::Path & path, const std::string & host, ErrorKind kind, const char * what)
{
  for (std::size_t i = 0; i < path.poses.size(); ++i) {
    if (!std::isfinite(path.poses[i])) {
      std::ostringstream message;
      message << what << host_part(host) << " has a non-finite value in pose "
              << i / protocol::kPoseRowSize << " of " << path.pose_count();
      throw CallError(kind, Cause::Local, message.str());
    }
  }
}

void check_window(
  const protocol::UpdateCostsReply & reply, const protocol::UpdateCostsRequest & request,
  const std::string & host)
{
  const std::int64_t width = request.max_i - request.min_i;
  const std::int64_t height = request.max_j - request.min_j;
  if (static_cast<std::int64_t>(reply.width) != width ||
    static_cast<std::int64_t>(reply.height) != height)
  {
    throw CallError(
            ErrorKind::ControllerException, Cause::BadReply,
            "update_costs reply" + host_part(host) + " is " + std::to_string(reply.width) +
            " x " + std::to_string(reply.height) + " cells, the window " + std::to_string(width) +
            " x " + std::to_string(height));
  }
}

void check_reply(
  const protocol::RequestBody & request, const protocol::ReplyBody & reply,
  const std::string & host)
{
  if (const auto * command = std::get_if<protocol::ComputeVelocityCommandsReply>(&reply)) {
    check_command(command->cmd_vel, host);
  } else if (const auto * step = std::get_if<protocol::OnCycleUpdateReply>(&reply)) {
    if (step->cmd_vel) {
      check_command(*step->cmd_vel, host);
    }
  } else if (const auto * plan = std::get_if<protocol::CreatePlanReply>(&reply)) {
    check_path(plan->path, host);
  } else if (const auto * smoothed = std::get_if<protocol::SmoothReply>(&reply)) {
    check_path(smoothed->path, host, ErrorKind::FailedToSmoothPath, "smooth reply");
  } else if (const auto * costs = std::get_if<protocol::UpdateCostsReply>(&reply)) {
    check_window(*costs, std::get<protocol::UpdateCostsRequest>(request), host);
  }
}

}  // namespace nav2_pyif_bridge::client
