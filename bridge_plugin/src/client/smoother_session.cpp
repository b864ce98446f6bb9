#include "nav2_pyif_bridge/client/smoother_session.hpp"

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
  auto reply = call_for<proto::SmoothReply>(body);
  check_path(reply.path, last_host(), ErrorKind::FailedToSmoothPath, "smooth reply");
  return reply;
}

}  // namespace nav2_pyif_bridge::client
