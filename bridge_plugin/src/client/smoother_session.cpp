#include "nav2_pyif_bridge/client/smoother_session.hpp"

#include <algorithm>
#include <chrono>

#include "nav2_pyif_bridge/client/command_check.hpp"

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

proto::SmoothReply SmootherSession::smooth(const proto::Path & path, double max_time)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::SmoothRequest body;
  body.path = path;
  body.max_time = max_time;
  CallOptions options;
  options.timeout = std::max(
    timeouts().plan, std::chrono::duration_cast<Duration>(
      std::chrono::duration<double>(max_time + proto::kSmoothGraceS)));
  auto reply = call_for<proto::SmoothReply>(body, options);
  check_path(reply.path, last_host(), ErrorKind::FailedToSmoothPath, "smooth reply");
  return reply;
}

}  // namespace nav2_pyif_bridge::client
