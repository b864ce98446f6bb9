#include "nav2_pyif_bridge/client/behavior_session.hpp"

#include <utility>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

namespace
{

BehaviorStep failed(const std::string & error)
{
  BehaviorStep step;
  step.error = error;
  return step;
}

}  // namespace

BehaviorStep BehaviorSession::step_of(
  const std::string & status, const std::string & failure, const char * what) const
{
  // "succeeded" / "failed" / "running" and the failure names, as the wire spells them
  const auto s = proto::from_name<BehaviorStatus>(proto::kBehaviorStatusNames, status);
  const auto f = proto::from_name<BehaviorFailure>(proto::kBehaviorFailureNames, failure);
  if (!s || !f) {
    return failed(
      std::string(what) + " reply from host " + current().last_host + " has status '" + status +
      "' and failure '" + failure + "'");
  }
  BehaviorStep step;
  step.status = *s;
  // FAILED always says why (UNKNOWN when the behaviour did not); the others never fail.
  step.failure = *s != BehaviorStatus::Failed ? BehaviorFailure::None :
    (*f == BehaviorFailure::None ? BehaviorFailure::Unknown : *f);
  return step;
}

BehaviorStep BehaviorSession::run(
  const std::string & action, const proto::Params & command, const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::OnRunRequest body;
  body.action = action;
  body.command = command;
  body.pose = pose;
  running_.reset();
  try {
    const auto reply = call(body);
    BehaviorStep step = step_of(reply.status, reply.failure, "on_run");
    if (step.status == BehaviorStatus::Running) {
      return failed("on_run reply from host " + current().last_host + " is 'running'");
    }
    if (step.status == BehaviorStatus::Succeeded) {
      running_ = std::move(body);
    }
    return step;
  } catch (const CallError & error) {
    return failed(error.log_text());
  }
}

BehaviorStep BehaviorSession::cycle_update(const proto::PoseStamped & pose, double elapsed)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  proto::OnCycleUpdateRequest body;
  body.pose = pose;
  body.elapsed = elapsed;
  try {
    auto reply = call(body);
    BehaviorStep step = step_of(reply.status, reply.failure, "on_cycle_update");
    if (!step.error.empty()) {
      return step;
    }
    if (step.status == BehaviorStatus::Running) {
      step.cmd_vel = std::move(reply.cmd_vel);
    }
    if (reply.feedback) {
      step.feedback = std::move(*reply.feedback);
    }
    return step;
  } catch (const CallError & error) {
    return failed(error.log_text());
  }
}

void BehaviorSession::action_completion(const std::string & status, double elapsed)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  running_.reset();
  proto::OnActionCompletionRequest body;
  body.status = status;
  body.elapsed = elapsed;
  try {
    call(body, {});
  } catch (const CallError & error) {
    log(logger(), LogLevel::Warn, "on_action_completion failed: " + error.log_text());
  }
}

bool BehaviorSession::running() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return running_.has_value();
}

std::optional<proto::RequestBody> BehaviorSession::restored(proto::Op op)
{
  if (op == proto::Op::OnRun && running_) {
    return *running_;
  }
  return std::nullopt;
}

}  // namespace nav2_pyif_bridge::client
