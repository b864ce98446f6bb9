// The goal and progress checkers' calls (the reference client's GoalCheckerClient and
// ProgressCheckerClient). Nav2 only initializes its checkers: the plugin configures at
// initialize and cleans up when destroyed; there is no state to re-send after a host restart.
#pragma once

#include <array>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class GoalCheckerSession : public KindSession<PluginKind::GoalChecker>
{
public:
  using KindSession::KindSession;

  // pose and goal: x, y, z, qx, qy, qz, qw in the costmap's global frame; velocity: vx, vy,
  // vz, wx, wy, wz in the robot base frame.
  bool is_goal_reached(
    const std::array<double, 7> & pose, const std::array<double, 7> & goal,
    const std::array<double, 6> & velocity);
  protocol::GetTolerancesReply get_tolerances();
  void reset();
};

class ProgressCheckerSession : public KindSession<PluginKind::ProgressChecker>
{
public:
  using KindSession::KindSession;

  // False when the robot failed to make progress.
  bool check(const protocol::PoseStamped & pose);
  void reset();
};

}  // namespace nav2_pyif_bridge::client
