// The controller's calls (the reference client's ControllerClient): set_plan, the control
// cycle, the speed limit, cancel and reset; the plan and speed limit are the state re-sent
// after a host restart.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class ControllerSession : public KindSession<PluginKind::Controller>
{
public:
  using KindSession::KindSession;

  // The plan in the costmap's global frame; remembered (after an ok reply) for re-sending.
  void set_plan(const protocol::Path & path);
  // The latest message of an input topic (from a subscription's thread): sent with the next
  // control cycle, once; every input again after the host lost the session.
  void set_input(protocol::Input input);
  // The debug outputs someone subscribes to, asked for in every following cycle.
  void set_debug_wanted(std::vector<std::string> names);
  // The debug outputs the last successful cycle returned (moved out).
  std::vector<protocol::DebugOutput> take_debug();

  // The command, every component finite (else NoValidControl). The costmap travels when it
  // changed since the host last got it, and so do the inputs.
  protocol::TwistStamped compute_velocity_commands(
    const protocol::PoseStamped & pose, const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker);
  // Remembered after an ok reply, and also when no host could be reached (the reference
  // client forgets it then), so a host that comes back drives at the latest limit.
  void set_speed_limit(double speed_limit, bool percentage);
  bool cancel();
  // `timeout` instead of the lifecycle one (Nav2 resets its controller at the end of every
  // goal, in the action's thread: the plugin keeps that short).
  void reset(std::optional<Duration> timeout = std::nullopt);

  bool has_plan() const;

protected:
  void restore_state() override;
  void forget_state() override;

private:
  std::optional<protocol::Path> plan_;
  std::optional<protocol::SetSpeedLimitRequest> speed_limit_;

  // The latest message of each input; `sent` is the generation the host acknowledged.
  struct LatestInput
  {
    protocol::Input input;
    std::uint64_t generation{0};
    std::uint64_t sent{0};
  };
  // Its own lock: subscription callbacks must not wait for a control cycle's round trip.
  mutable std::mutex inputs_mutex_;
  std::map<std::string, LatestInput> inputs_;
  std::vector<std::string> debug_wanted_;
  std::vector<protocol::DebugOutput> debug_;
};

}  // namespace nav2_pyif_bridge::client
