// The goal and progress checkers' calls (the reference client's GoalCheckerClient and
// ProgressCheckerClient). Nav2 only initializes its checkers: the plugin configures at
// initialize and cleans up when destroyed; there is no state to re-send after a host restart.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

// A request the goal check's query carries for another key (PROTOCOL.md section 15).
struct CarriedCall
{
  std::string key;        // the key prefix of the plugin it is for
  protocol::Bytes payload;
};

// The goal check's answer and the encoded replies of the calls it carried, those that ran.
struct GoalCheckReplies
{
  bool reached{false};
  std::optional<protocol::Bytes> check;
  std::optional<protocol::Bytes> compute;
};

// The progress check's answer and the encoded reply of the command it carried, if that ran.
struct CheckReplies
{
  bool making_progress{false};
  std::optional<protocol::Bytes> compute;
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
  // The same, carrying the progress check and the command of the cycle (either may be
  // absent); the host runs them in Nav2's order, as far as Nav2 would go.
  GoalCheckReplies is_goal_reached(
    const std::array<double, 7> & pose, const std::array<double, 7> & goal,
    const std::array<double, 6> & velocity, std::optional<CarriedCall> then_check,
    std::optional<CarriedCall> then_compute);
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
  CheckReplies check(const protocol::PoseStamped & pose, std::optional<CarriedCall> then_compute);
  // The same call prepared for the goal check's query to carry; std::nullopt when the
  // session cannot prepare one now.
  std::optional<Carried> prepare_check(const protocol::PoseStamped & pose);
  // The answer from the carried reply, when Nav2's call is the prepared one (the same pose,
  // header included) and it ran; else std::nullopt: the call goes on its own.
  std::optional<bool> settle_check(
    const Carried & carried, const std::optional<protocol::Bytes> & reply,
    const protocol::PoseStamped & pose);
  void reset();
};

}  // namespace nav2_pyif_bridge::client
