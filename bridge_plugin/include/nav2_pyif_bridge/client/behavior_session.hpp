// The behaviour's calls (the reference client's BehaviorClient): TimedBehavior's onRun,
// onCycleUpdate and onActionCompletion. A behaviour never throws into behavior_server: every
// failure of a call (no host, no reply in time, a Python exception, a bad answer) is a FAILED
// step with the UNKNOWN failure and the error's log text, and the plugin stops the robot.
#pragma once

#include <optional>
#include <string>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

// TimedBehavior's Status, and why a behaviour failed: the action result's error code of that
// name (PROTOCOL.md section 17); their wire names are generated from constants.py.
using protocol::BehaviorFailure;
using protocol::BehaviorStatus;

struct BehaviorStep
{
  BehaviorStatus status{BehaviorStatus::Failed};
  BehaviorFailure failure{BehaviorFailure::Unknown};
  std::optional<protocol::TwistStamped> cmd_vel;  // only with Running, every component finite
  protocol::Params feedback;
  std::string error;  // the failed call's log text (message and traceback), empty when none
};

class BehaviorSession : public KindSession<PluginKind::Behavior>
{
public:
  using KindSession::KindSession;

  // The action's goal (`action` e.g. nav2_msgs/action/BackUp, its fields as plain values) at
  // `pose` (behavior_server's local frame); Succeeded starts the cycle. Never throws.
  BehaviorStep run(
    const std::string & action, const protocol::Params & command,
    const protocol::PoseStamped & pose);
  // One cycle, `elapsed` seconds after run. Never throws.
  BehaviorStep cycle_update(const protocol::PoseStamped & pose, double elapsed);
  // The action ended ("succeeded", "failed", "cancelled"); an error is logged, never thrown.
  void action_completion(const std::string & status, double elapsed);

  // Whether an action is under way (run succeeded, no completion yet).
  bool running() const;

protected:
  // A re-established session is given the action under way again (its on_run), so the new
  // host goes on with it from where it started.
  std::optional<protocol::RequestBody> restored(protocol::Op op) override;
  void forget_state() override {running_.reset();}

private:
  BehaviorStep step_of(
    const std::string & status, const std::string & failure, const char * what) const;

  std::optional<protocol::OnRunRequest> running_;
};

}  // namespace nav2_pyif_bridge::client
