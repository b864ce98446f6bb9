// The goal and progress checkers' calls (the reference client's GoalCheckerClient and
// ProgressCheckerClient). Nav2 only initializes its checkers: the plugin configures at
// initialize and cleans up when destroyed; there is no state to re-send after a host restart.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

// The encoded requests a call's query carries for other keys, or the encoded replies of
// those that ran, in order (PROTOCOL.md section 15).
using CarriedCalls = std::vector<protocol::CarriedCall>;

// The goal check's answer and the replies of the calls it carried.
struct GoalCheckReplies
{
  bool reached{false};
  CarriedCalls carried;
};

// The progress check's answer and the replies of the calls it carried.
struct CheckReplies
{
  bool making_progress{false};
  CarriedCalls carried;
};

class GoalCheckerSession : public KindSession<PluginKind::GoalChecker>
{
public:
  using KindSession::KindSession;

  // pose and goal: x, y, z, qx, qy, qz, qw in the costmap's global frame; velocity: vx, vy,
  // vz, wx, wy, wz in the robot base frame.
  bool is_goal_reached(
    const std::array<double, 7> & pose, const std::array<double, 7> & goal,
    const std::array<double, 6> & velocity);
  // The same, carrying the calls that follow it in the cycle; the host runs them in order,
  // as far as Nav2 would go.
  GoalCheckReplies is_goal_reached(
    const std::array<double, 7> & pose, const std::array<double, 7> & goal,
    const std::array<double, 6> & velocity, CarriedCalls carry);
  // The same call prepared for another plugin's query to carry; std::nullopt when the
  // session cannot prepare one now.
  std::optional<Carried> prepare_goal_check(
    const std::array<double, 7> & pose, const std::array<double, 7> & goal,
    const std::array<double, 6> & velocity);
  // The answer from the carried reply when Nav2's call is the prepared one
  // (PluginSession::take); else std::nullopt: the call goes on its own.
  std::optional<bool> take_goal_check(
    Carried carried, const std::optional<protocol::Bytes> & reply,
    const std::array<double, 7> & pose, const std::array<double, 7> & goal,
    const std::array<double, 6> & velocity);
  // Lyrical's isGoalXYReached: the position only (never carried: Nav2's own controllers call
  // it, not controller_server's cycle).
  bool is_goal_xy_reached(
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
  // The same, carrying the command of the cycle; the host runs it when Nav2 would (progress).
  CheckReplies check(const protocol::PoseStamped & pose, CarriedCalls carry);
  // As GoalCheckerSession's prepare_goal_check and take_goal_check.
  std::optional<Carried> prepare_check(const protocol::PoseStamped & pose);
  std::optional<bool> take_check(
    Carried carried, const std::optional<protocol::Bytes> & reply,
    const protocol::PoseStamped & pose);
  void reset();
};

}  // namespace nav2_pyif_bridge::client
