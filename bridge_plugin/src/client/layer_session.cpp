#include "nav2_pyif_bridge/client/layer_session.hpp"

#include <string>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

proto::UpdateBoundsReply CostmapLayerSession::update_bounds(
  const proto::UpdateBoundsRequest & request)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return call_for<proto::UpdateBoundsReply>(request);
}

proto::UpdateCostsReply CostmapLayerSession::update_costs(const proto::UpdateCostsRequest & request)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  auto reply = call_for<proto::UpdateCostsReply>(request);
  const std::int64_t width = request.max_i - request.min_i;
  const std::int64_t height = request.max_j - request.min_j;
  if (static_cast<std::int64_t>(reply.width) != width ||
    static_cast<std::int64_t>(reply.height) != height)
  {
    fail(
      ErrorKind::ControllerException, Cause::BadReply,
      "update_costs reply from host " + last_host() + " is " + std::to_string(reply.width) +
      " x " + std::to_string(reply.height) + " cells, the window " + std::to_string(width) +
      " x " + std::to_string(height));
  }
  return reply;
}

void CostmapLayerSession::match_size(const proto::MatchSizeRequest & request)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  call(request, {});
}

void CostmapLayerSession::reset()
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  call(proto::ResetRequest{}, {});
}

}  // namespace nav2_pyif_bridge::client
