#include "nav2_pyif_bridge/client/checker_sessions.hpp"

#include <utility>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

bool GoalCheckerSession::is_goal_reached(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  return is_goal_reached(pose, goal, velocity, {}).reached;
}

namespace
{

proto::IsGoalReachedRequest goal_check(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  proto::IsGoalReachedRequest body;
  body.pose = pose;
  body.goal = goal;
  body.velocity = velocity;
  return body;
}

std::optional<std::vector<proto::CarriedCall>> some(CarriedCalls carry)
{
  return carry.empty() ? std::nullopt : std::make_optional(std::move(carry));
}

}  // namespace

GoalCheckReplies GoalCheckerSession::is_goal_reached(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity, CarriedCalls carry)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::IsGoalReachedRequest body = goal_check(pose, goal, velocity);
  body.carry = some(std::move(carry));
  auto reply = call_for<proto::IsGoalReachedReply>(body);
  return {reply.reached, reply.carried.value_or(CarriedCalls{})};
}

std::optional<Carried> GoalCheckerSession::prepare_goal_check(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return prepare(goal_check(pose, goal, velocity));
}

std::optional<bool> GoalCheckerSession::take_goal_check(
  Carried carried, const std::optional<proto::Bytes> & reply,
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  auto body = take(std::move(carried), reply, goal_check(pose, goal, velocity));
  if (!body) {
    return std::nullopt;
  }
  return std::get<proto::IsGoalReachedReply>(*body).reached;
}

bool GoalCheckerSession::is_goal_xy_reached(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::IsGoalReachedRequest body = goal_check(pose, goal, velocity);
  body.xy_only = true;
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
  return check(pose, {}).making_progress;
}

CheckReplies ProgressCheckerSession::check(const proto::PoseStamped & pose, CarriedCalls carry)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::CheckRequest body;
  body.pose = pose;
  body.carry = some(std::move(carry));
  auto reply = call_for<proto::CheckReply>(body);
  return {reply.making_progress, reply.carried.value_or(CarriedCalls{})};
}

std::optional<Carried> ProgressCheckerSession::prepare_check(const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::CheckRequest body;
  body.pose = pose;
  return prepare(body);
}

std::optional<bool> ProgressCheckerSession::take_check(
  Carried carried, const std::optional<proto::Bytes> & reply, const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::CheckRequest body;
  body.pose = pose;
  auto answer = take(std::move(carried), reply, body);
  if (!answer) {
    return std::nullopt;
  }
  return std::get<proto::CheckReply>(*answer).making_progress;
}

void ProgressCheckerSession::reset()
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  call(proto::ResetRequest{}, {});
}

}  // namespace nav2_pyif_bridge::client
