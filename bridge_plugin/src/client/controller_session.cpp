#include "nav2_pyif_bridge/client/controller_session.hpp"

#include <utility>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

std::optional<CallError> ControllerSession::set_plan(const proto::Path & path)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  plan_ = path;
  plan_owed_ = true;
  try {
    send_plan();
  } catch (const CallError & error) {
    if (!error.host_failed()) {
      plan_owed_ = false;
      throw;
    }
    return error;
  }
  return std::nullopt;
}

void ControllerSession::send_plan()
{
  call(proto::SetPlanRequest{*plan_, goal_}, {});
  plan_owed_ = false;
  plan_unsent_ = false;
  goal_unsent_ = false;
}

namespace
{

// Equal but for the stamp (controller_server stamps the plan and goal anew every cycle).
bool same_place(const proto::Path & a, const proto::Path & b)
{
  return a.frame_id == b.frame_id && a.poses == b.poses;
}

bool same_place(const proto::PoseStamped & a, const proto::PoseStamped & b)
{
  return a.frame_id == b.frame_id && a.pose == b.pose;
}

}  // namespace

void ControllerSession::follow(const proto::Path & plan, const proto::PoseStamped & goal)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  follows_cycle_plan_ = true;
  if (!plan_ || !same_place(*plan_, plan)) {
    plan_ = plan;
    plan_unsent_ = true;
  }
  if (!goal_ || !same_place(*goal_, goal)) {
    goal_ = goal;
    goal_unsent_ = true;
  }
}

CommandReplies ControllerSession::compute_velocity_commands(
  const proto::PoseStamped & pose, const std::array<double, 6> & velocity,
  const std::optional<proto::GoalChecker> & goal_checker, std::vector<proto::CarriedCall> carry)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (plan_owed_) {
    send_plan();  // a host failure here fails this cycle, as the cycle's own would
  }
  Attached attached;
  auto reply =
    call(carrying(command_body(pose, velocity, goal_checker, attached), std::move(carry)));
  std::vector<proto::CarriedCall> carried = std::move(reply.carried).value_or(
    std::vector<proto::CarriedCall>{});
  return {command_of(std::move(reply), attached), std::move(carried)};
}

std::optional<Carried> ControllerSession::prepare_command(
  const proto::PoseStamped & pose, const std::array<double, 6> & velocity,
  const std::optional<proto::GoalChecker> & goal_checker)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (plan_owed_ || follows_cycle_plan_) {
    return std::nullopt;  // it would run on the host's old plan
  }
  Attached attached;  // acknowledged by take_command, which attaches the same
  return prepare(command_body(pose, velocity, goal_checker, attached));
}

std::optional<proto::TwistStamped> ControllerSession::take_command(
  Carried prepared, const std::optional<proto::Bytes> & reply,
  const proto::PoseStamped & pose, const std::array<double, 6> & velocity,
  const std::optional<proto::GoalChecker> & goal_checker)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (plan_owed_) {
    return std::nullopt;  // set_plan sent nothing (no host): the plan is news to the host too
  }
  // Taken only when it encodes to the prepared bytes: the same plan, goal and inputs attached
  Attached attached;
  auto body =
    take(std::move(prepared), reply, command_body(pose, velocity, goal_checker, attached));
  if (!body) {
    return std::nullopt;
  }
  return command_of(std::move(*body), attached);
}

proto::ComputeVelocityCommandsRequest ControllerSession::command_body(
  const proto::PoseStamped & pose, const std::array<double, 6> & velocity,
  const std::optional<proto::GoalChecker> & goal_checker, Attached & attached)
{
  proto::ComputeVelocityCommandsRequest body;
  body.pose = pose;
  body.velocity = velocity;
  body.goal_checker = goal_checker;
  if (plan_unsent_) {
    body.plan = plan_;
    attached.plan = true;
  }
  if (goal_unsent_) {
    body.goal = goal_;
    attached.goal = true;
  }
  const std::uint64_t session = current().epoch;
  std::lock_guard<std::mutex> inputs_lock(inputs_mutex_);
  for (const auto & [name, latest] : inputs_) {
    if (latest.sent != latest.generation || latest.sent_epoch != session) {
      if (!body.inputs) {
        body.inputs.emplace();
      }
      body.inputs->push_back(latest.input);
      attached.inputs.emplace_back(name, latest.generation);
    }
  }
  if (!debug_wanted_.empty()) {
    body.debug_wanted = debug_wanted_;
  }
  return body;
}

proto::TwistStamped ControllerSession::command_of(
  proto::ComputeVelocityCommandsReply reply, const Attached & attached)
{
  // (the caller holds mutex(): plan_ and goal_ are still what was attached)
  plan_unsent_ = plan_unsent_ && !attached.plan;
  goal_unsent_ = goal_unsent_ && !attached.goal;
  const std::uint64_t session = current().epoch;
  std::lock_guard<std::mutex> inputs_lock(inputs_mutex_);
  for (const auto & [name, generation] : attached.inputs) {
    inputs_[name].sent = generation;
    inputs_[name].sent_epoch = session;
  }
  debug_ = reply.debug ? std::move(*reply.debug) : std::vector<proto::DebugOutput>{};
  return std::move(reply.cmd_vel);
}

void ControllerSession::set_input(proto::Input input)
{
  std::lock_guard<std::mutex> lock(inputs_mutex_);
  LatestInput & latest = inputs_[input.name];
  latest.input = std::move(input);
  ++latest.generation;
}

void ControllerSession::set_debug_wanted(std::vector<std::string> names)
{
  std::lock_guard<std::mutex> lock(inputs_mutex_);
  debug_wanted_ = std::move(names);
}

std::vector<proto::DebugOutput> ControllerSession::take_debug()
{
  std::lock_guard<std::mutex> lock(inputs_mutex_);
  return std::exchange(debug_, {});
}

void ControllerSession::set_speed_limit(double speed_limit, bool percentage)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  const proto::SetSpeedLimitRequest body{speed_limit, percentage};
  try {
    call(body, {});
  } catch (const CallError & error) {
    if (error.host_failed()) {
      speed_limit_ = body;  // a speed zone must not be forgotten: the next host gets it
    }
    throw;
  }
  speed_limit_ = body;
}

bool ControllerSession::has_plan() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return plan_.has_value();
}

std::optional<proto::RequestBody> ControllerSession::restored(proto::Op op)
{
  if (op == proto::Op::SetPlan && plan_ && !plan_owed_) {  // an owed one: its call sends it
    plan_unsent_ = goal_unsent_ = false;  // set_plan gives both
    return proto::SetPlanRequest{*plan_, goal_};
  }
  if (op == proto::Op::SetSpeedLimit && speed_limit_) {
    return *speed_limit_;
  }
  return std::nullopt;
}

void ControllerSession::forget_state()
{
  plan_.reset();
  plan_owed_ = false;
  goal_.reset();
  plan_unsent_ = false;
  goal_unsent_ = false;
  follows_cycle_plan_ = false;
  speed_limit_.reset();
}

}  // namespace nav2_pyif_bridge::client
