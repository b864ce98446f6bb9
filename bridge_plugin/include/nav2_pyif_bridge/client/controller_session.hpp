// The controller's calls (the reference client's ControllerClient): set_plan, the control
// cycle, the speed limit, cancel and reset; the plan and speed limit are the state re-sent
// after a host restart.
#pragma once

#include <array>
#include <optional>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class ControllerSession : public KindSession<PluginKind::Controller>
{
public:
  using KindSession::KindSession;

  // The plan in the costmap's global frame; remembered (after an ok reply) for re-sending.
  void set_plan(const protocol::Path & path);
  // The command, every component finite (else NoValidControl). The costmap travels when it
  // changed since the host last got it.
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
};

}  // namespace nav2_pyif_bridge::client
