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

void CarriedCycle::forget(const PluginSession & session)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (controller_ == &session) {
    controller_ = nullptr;
  }
  if (progress_checker_ == &session) {
    progress_checker_ = nullptr;
  }
  if (check_ && check_->session == &session) {
    check_.reset();
  }
  if (compute_ && compute_->session == &session) {
    compute_.reset();
  }
}

bool CarriedCycle::is_goal_reached(
  GoalCheckerSession & checker, const proto::PoseStamped & pose,
  const std::array<double, 7> & goal, const std::array<double, 6> & velocity,
  const std::optional<proto::GoalChecker> & tolerances)
{
  std::optional<PendingCheck> check;
  std::optional<PendingCompute> compute;
  std::optional<CarriedCall> then_check;
  std::optional<CarriedCall> then_compute;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    check_.reset();  // a previous cycle's, unused: Nav2 went another way
    compute_.reset();
    command_inputs_ = CommandInputs{velocity, tolerances};
    if (progress_checker_ != nullptr) {
      if (auto carried = progress_checker_->prepare_check(pose)) {
        then_check = CarriedCall{progress_checker_->keys().prefix(), carried->payload};
        check = PendingCheck{progress_checker_, std::move(*carried), std::nullopt};
      }
    }
    if (controller_ != nullptr) {
      if (auto prepared = controller_->prepare_command(pose, velocity, tolerances)) {
        then_compute = CarriedCall{controller_->keys().prefix(), prepared->carried.payload};
        compute = PendingCompute{controller_, std::move(*prepared), std::nullopt};
      }
    }
  }
  GoalCheckReplies replies = checker.is_goal_reached(
    pose.pose, goal, velocity, std::move(then_check), std::move(then_compute));
  std::lock_guard<std::mutex> lock(mutex_);
  // Kept only for the sessions still in use (one may have been cleaned up meanwhile).
  if (check && check->session == progress_checker_) {
    check->reply = std::move(replies.check);
    check_ = std::move(check);
  }
  if (compute && compute->session == controller_) {
    compute->reply = std::move(replies.compute);
    compute_ = std::move(compute);
  }
  return replies.reached;
}

std::optional<bool> CarriedCycle::take_check(
  ProgressCheckerSession & session, const proto::PoseStamped & pose)
{
  std::optional<PendingCheck> pending;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!check_ || check_->session != &session) {
      return std::nullopt;
    }
    pending = std::exchange(check_, std::nullopt);
  }
  std::optional<bool> answer = session.settle_check(pending->carried, pending->reply, pose);
  std::lock_guard<std::mutex> lock(mutex_);
  ++(answer ? carried_used_ : sent_alone_);
  return answer;
}

bool CarriedCycle::check(ProgressCheckerSession & session, const proto::PoseStamped & pose)
{
  if (const std::optional<bool> carried = take_check(session, pose)) {
    return *carried;
  }
  std::optional<PendingCompute> compute;
  std::optional<CarriedCall> then_compute;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::optional<CommandInputs> inputs = std::exchange(command_inputs_, std::nullopt);
    const bool still_fits = compute_ && same_pose(compute_->prepared.pose, pose);
    if (inputs && controller_ != nullptr && !still_fits) {
      compute_.reset();  // prepared for the goal check's pose
      if (auto prepared = controller_->prepare_command(pose, inputs->velocity, inputs->tolerances))
      {
        then_compute = CarriedCall{controller_->keys().prefix(), prepared->carried.payload};
        compute = PendingCompute{controller_, std::move(*prepared), std::nullopt};
      }
    }
  }
  CheckReplies replies = session.check(pose, std::move(then_compute));
  std::lock_guard<std::mutex> lock(mutex_);
  if (compute && compute->session == controller_) {
    compute->reply = std::move(replies.compute);
    compute_ = std::move(compute);
  }
  return replies.making_progress;
}

std::optional<proto::TwistStamped> CarriedCycle::take_compute(
  ControllerSession & session, const proto::PoseStamped & pose,
  const std::array<double, 6> & velocity, const std::optional<proto::GoalChecker> & goal_checker)
{
  std::optional<PendingCompute> pending;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!compute_ || compute_->session != &session) {
      return std::nullopt;
    }
    pending = std::exchange(compute_, std::nullopt);
  }
  std::optional<proto::TwistStamped> command =
    session.settle_command(pending->prepared, pending->reply, pose, velocity, goal_checker);
  std::lock_guard<std::mutex> lock(mutex_);
  ++(command ? carried_used_ : sent_alone_);
  return command;
}

std::uint64_t CarriedCycle::carried_used() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return carried_used_;
}

std::uint64_t CarriedCycle::sent_alone() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return sent_alone_;
}

}  // namespace nav2_pyif_bridge::client
