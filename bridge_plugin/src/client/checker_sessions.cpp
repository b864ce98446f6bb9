#include "nav2_pyif_bridge/client/checker_sessions.hpp"

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

bool GoalCheckerSession::is_goal_reached(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::IsGoalReachedRequest body;
  body.pose = pose;
  body.goal = goal;
  body.velocity = velocity;
  return call_for<proto::IsGoalReachedReply>(body).reached;
}

proto::GetTolerancesReply GoalCheckerSession::get_tolerances()
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return call_for<proto::GetTolerancesReply>(proto::GetTolerancesRequest{});
}

void GoalCheckerSession::reset()
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  call(proto::ResetRequest{}, {});
}

bool ProgressCheckerSession::check(const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::CheckRequest body;
  body.pose = pose;
  return call_for<proto::CheckReply>(body).making_progress;
}

void ProgressCheckerSession::reset()
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  call(proto::ResetRequest{}, {});
}

}  // namespace nav2_pyif_bridge::client
