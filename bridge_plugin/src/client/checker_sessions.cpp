#include "nav2_pyif_bridge/client/checker_sessions.hpp"

#include <utility>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

bool GoalCheckerSession::is_goal_reached(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  return is_goal_reached(pose, goal, velocity, std::nullopt, std::nullopt).reached;
}

GoalCheckReplies GoalCheckerSession::is_goal_reached(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity, std::optional<CarriedCall> then_check,
  std::optional<CarriedCall> then_compute)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::IsGoalReachedRequest body;
  body.pose = pose;
  body.goal = goal;
  body.velocity = velocity;
  if (then_check) {
    body.then_check_key = std::move(then_check->key);
    body.then_check = std::move(then_check->payload);
  }
  if (then_compute) {
    body.then_compute_key = std::move(then_compute->key);
    body.then_compute = std::move(then_compute->payload);
  }
  auto reply = call_for<proto::IsGoalReachedReply>(body);
  return {reply.reached, std::move(reply.then_check), std::move(reply.then_compute)};
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
  return check(pose, std::nullopt).making_progress;
}

CheckReplies ProgressCheckerSession::check(
  const proto::PoseStamped & pose, std::optional<CarriedCall> then_compute)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::CheckRequest body;
  body.pose = pose;
  if (then_compute) {
    body.then_compute_key = std::move(then_compute->key);
    body.then_compute = std::move(then_compute->payload);
  }
  auto reply = call_for<proto::CheckReply>(body);
  return {reply.making_progress, std::move(reply.then_compute)};
}

std::optional<Carried> ProgressCheckerSession::prepare_check(const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::CheckRequest body;
  body.pose = pose;
  return prepare(body, CostmapMode::None);
}

std::optional<bool> ProgressCheckerSession::settle_check(
  const Carried & carried, const std::optional<proto::Bytes> & reply,
  const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (!same_pose(std::get<proto::CheckRequest>(carried.request.body).pose, pose)) {
    return std::nullopt;
  }
  auto body = settle(carried, reply);
  if (!body) {
    return std::nullopt;
  }
  return std::get<proto::CheckReply>(*body).making_progress;
}

void ProgressCheckerSession::reset()
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  call(proto::ResetRequest{}, {});
}

}  // namespace nav2_pyif_bridge::client
