#include "nav2_pyif_bridge/client/carried_cycle.hpp"

#include <map>
#include <utility>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

std::shared_ptr<CarriedCycle> CarriedCycle::of(const std::string & node)
{
  static std::mutex registry_mutex;
  static std::map<std::string, std::weak_ptr<CarriedCycle>> registry;
  std::lock_guard<std::mutex> lock(registry_mutex);
  std::shared_ptr<CarriedCycle> cycle = registry[node].lock();
  if (!cycle) {
    cycle = std::make_shared<CarriedCycle>();
    registry[node] = cycle;
  }
  return cycle;
}

void CarriedCycle::use_controller(ControllerSession & session)
{
  std::lock_guard<std::mutex> lock(mutex_);
  controller_ = &session;
}

void CarriedCycle::use_progress_checker(ProgressCheckerSession & session)
{
  std::lock_guard<std::mutex> lock(mutex_);
  progress_checker_ = &session;
}

void CarriedCycle::use_path_handler(PathHandlerSession & session)
{
  std::lock_guard<std::mutex> lock(mutex_);
  path_handler_ = &session;
}

void CarriedCycle::forget(const PluginSession & session)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (controller_ == &session) {
    controller_ = nullptr;
  }
  if (path_handler_ == &session) {
    path_handler_ = nullptr;
  }
  if (segment_ && segment_->session == &session) {
    segment_.reset();
  }
  if (progress_checker_ == &session) {
    progress_checker_ = nullptr;
  }
  if (goal_checker_ == &session) {
    goal_checker_ = nullptr;
  }
  if (check_ && check_->session == &session) {
    check_.reset();
  }
  if (compute_ && compute_->session == &session) {
    compute_.reset();
  }
  if (goal_check_ && goal_check_->session == &session) {
    goal_check_.reset();
  }
}

std::optional<CarriedCycle::Pending> CarriedCycle::take_for(
  std::optional<Pending> & slot, const PluginSession & session)
{
  // (emptied either way: a call prepared for another session is not coming)
  std::optional<Pending> pending = std::exchange(slot, std::nullopt);
  if (pending && pending->session != &session) {
    pending.reset();
  }
  return pending;
}

std::optional<CarriedCycle::Pending> CarriedCycle::add(
  CarriedCalls & carry, const PluginSession & session, std::optional<Carried> prepared)
{
  if (!prepared) {
    return std::nullopt;
  }
  carry.push_back(proto::CarriedCall{session.keys().prefix(), prepared->payload});
  return Pending{&session, std::move(*prepared), std::nullopt};
}

void CarriedCycle::keep(
  std::optional<Pending> & slot, std::optional<Pending> pending, CarriedCalls & replies,
  std::size_t & next, const PluginSession * current)
{
  if (!pending) {
    return;
  }
  if (next < replies.size()) {
    pending->reply = std::move(replies[next].payload);
  }
  ++next;
  if (pending->session == current) {  // not cleaned up meanwhile
    slot = std::move(pending);
  }
}

void CarriedCycle::prepare_rest(
  CarriedCalls & carry, const proto::PoseStamped & pose, const CommandInputs & inputs,
  std::optional<Pending> & segment, std::optional<Pending> & compute)
{
  if (path_handler_ != nullptr) {
    segment = add(carry, *path_handler_, path_handler_->prepare_segment(pose));
  } else if (controller_ != nullptr) {
    compute = add(
      carry, *controller_,
      controller_->prepare_command(pose, inputs.velocity, inputs.tolerances));
  }
}

void CarriedCycle::learn(bool goal_last_seen, bool seen)
{
  (goal_last_seen ? seen_last_ : seen_first_) = seen;
  if (seen_last_ != seen_first_) {
    goal_last_ = seen_last_;
  }
}

void CarriedCycle::count(bool carried)
{
  std::lock_guard<std::mutex> lock(mutex_);
  carried_used_ += carried ? 1 : 0;
}

bool CarriedCycle::is_goal_reached(
  GoalCheckerSession & checker, const std::optional<proto::PoseStamped> & robot,
  const proto::IsGoalReachedRequest & request,
  const std::optional<proto::GoalChecker> & tolerances)
{
  const std::array<double, 6> & velocity = request.velocity;
  std::optional<Pending> mine;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_goal_check_ = Seen{request.pose, velocity};
    learn(true, last_command_ == last_goal_check_);
    goal_checker_ = &checker;
    mine = take_for(goal_check_, checker);
  }
  std::optional<bool> reached;
  if (mine) {
    if (auto reply = checker.take(std::move(mine->prepared), mine->reply, request)) {
      reached = reply->reached;
    }
    count(reached.has_value());
  }
  if (!reached) {
    std::optional<Pending> check;
    std::optional<Pending> segment;
    std::optional<Pending> compute;
    CarriedCalls carry;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      check_.reset();  // a previous cycle's, unused: Nav2 went another way
      segment_.reset();
      compute_.reset();
      if (!goal_last_ && robot) {
        command_inputs_ = CommandInputs{*robot, velocity, tolerances};
        if (progress_checker_ != nullptr) {
          check =
            add(carry, *progress_checker_, progress_checker_->prepare(progress_check(*robot)));
        }
        prepare_rest(carry, *robot, *command_inputs_, segment, compute);
      }
    }
    proto::IsGoalReachedReply reply = checker.call(carrying(request, std::move(carry)));
    CarriedCalls replies = std::move(reply.carried).value_or(CarriedCalls{});
    std::lock_guard<std::mutex> lock(mutex_);
    std::size_t next = 0;
    keep(check_, std::move(check), replies, next, progress_checker_);
    keep(segment_, std::move(segment), replies, next, path_handler_);
    keep(compute_, std::move(compute), replies, next, controller_);
    reached = reply.reached;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  goal_ = request.goal;  // what a command's query may carry next, until the checker is reset
  goal_seq_ = checker.last_seq();
  return *reached;
}

bool CarriedCycle::check(ProgressCheckerSession & session, const proto::CheckRequest & request)
{
  const proto::PoseStamped & pose = request.pose;
  std::optional<Pending> mine;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    mine = take_for(check_, session);
  }
  if (mine) {
    const std::optional<proto::CheckReply> carried =
      session.take(std::move(mine->prepared), mine->reply, request);
    count(carried.has_value());
    if (carried) {
      return carried->making_progress;
    }
  }
  std::optional<Pending> segment;
  std::optional<Pending> compute;
  CarriedCalls carry;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::optional<CommandInputs> inputs = std::exchange(command_inputs_, std::nullopt);
    // Goal first, TF moved on since the goal check: the calls prepared for it will not fit
    if (!goal_last_ && inputs && !same_pose(inputs->pose, pose)) {
      segment_.reset();
      compute_.reset();
      prepare_rest(carry, pose, *inputs, segment, compute);
    }
  }
  proto::CheckReply reply = session.call(carrying(request, std::move(carry)));
  CarriedCalls replies = std::move(reply.carried).value_or(CarriedCalls{});
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t next = 0;
  keep(segment_, std::move(segment), replies, next, path_handler_);
  keep(compute_, std::move(compute), replies, next, controller_);
  return reply.making_progress;
}

std::pair<std::size_t, std::size_t> CarriedCycle::find_plan_segment(
  PathHandlerSession & session, const proto::PoseStamped & pose)
{
  std::optional<Pending> mine;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    mine = take_for(segment_, session);
  }
  if (mine) {
    auto carried = session.take_segment(std::move(mine->prepared), mine->reply, pose);
    count(carried.has_value());
    if (carried) {
      return *carried;
    }
  }
  return session.find_plan_segment(pose);
}

proto::TwistStamped CarriedCycle::compute_velocity_commands(
  ControllerSession & session, const proto::PoseStamped & pose,
  const std::array<double, 6> & velocity, const std::optional<proto::GoalChecker> & goal_checker)
{
  std::optional<Pending> mine;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    command_inputs_.reset();
    last_command_ = Seen{pose.pose, velocity};
    learn(false, last_goal_check_ == last_command_);
    mine = take_for(compute_, session);
  }
  if (mine) {
    std::optional<proto::TwistStamped> carried = session.take_command(
      std::move(mine->prepared), mine->reply, pose, velocity, goal_checker);
    count(carried.has_value());
    if (carried) {
      return std::move(*carried);
    }
  }
  std::optional<Pending> goal_check;
  CarriedCalls carry;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    goal_check_.reset();
    // Goal last: the goal check for the goal its checker was last given, unless it was
    // reset since (controller_server resets it with every new plan)
    if (goal_last_ && goal_ && goal_checker_ != nullptr && goal_checker_->last_seq() == goal_seq_) {
      const auto request = client::goal_check(pose.pose, *goal_, velocity);
      goal_check = add(carry, *goal_checker_, goal_checker_->prepare(request));
    }
  }
  CommandReplies replies =
    session.compute_velocity_commands(pose, velocity, goal_checker, std::move(carry));
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t next = 0;
  keep(goal_check_, std::move(goal_check), replies.carried, next, goal_checker_);
  return std::move(replies.cmd_vel);
}

std::uint64_t CarriedCycle::carried_used() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return carried_used_;
}

bool CarriedCycle::goal_last() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return goal_last_;
}

}  // namespace nav2_pyif_bridge::client
