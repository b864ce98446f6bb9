// PROTOCOL.md section 15 on the plugin side: in one controller_server, the Python goal
// checker's query carries the Python progress checker's check and the Python controller's
// command, prepared for the same pose and velocity; the progress checker and the controller
// use the carried replies when Nav2 then calls them with those very inputs, and call on their
// own otherwise (other inputs, a call that did not run, another host): one round trip per
// control cycle instead of three, and always Nav2's outcome.
//
// Nav2 does not tell a goal checker which controller and progress checker it calls next: the
// cycle holds the controller that got the latest plan and the progress checker reset last
// (controller_server resets the current one at every new goal). A wrong guess costs one
// prepared call the host runs and nobody uses.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "nav2_pyif_bridge/client/checker_sessions.hpp"
#include "nav2_pyif_bridge/client/controller_session.hpp"

namespace nav2_pyif_bridge::client
{

class CarriedCycle
{
public:
  // The cycle of one controller_server node (by its fully qualified name), shared by the
  // plugins in it; it lives as long as one of them holds it.
  static std::shared_ptr<CarriedCycle> of(const std::string & node);

  // The controller (progress checker) the next goal checks prepare for; forget() before the
  // session is destroyed.
  void use_controller(ControllerSession & session);
  void use_progress_checker(ProgressCheckerSession & session);
  void forget(const PluginSession & session);

  // The goal check for the robot's `pose` (the message Nav2's pose lookup gives, header
  // included), carrying the check and the command prepared for it.
  bool is_goal_reached(
    GoalCheckerSession & checker, const protocol::PoseStamped & pose,
    const std::array<double, 7> & goal, const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & tolerances);

  // The carried answer for this call, if it is the prepared one; taken once. std::nullopt:
  // call on your own.
  std::optional<bool> take_check(
    ProgressCheckerSession & session, const protocol::PoseStamped & pose);
  // The progress check of this cycle: the carried answer when it was prepared for `pose`;
  // else the check on its own, carrying the command prepared for `pose` with the goal check's
  // velocity and tolerances when TF moved on since the goal check (Nav2 gives the progress
  // checker and the controller the same pose): two round trips that cycle, not three.
  bool check(ProgressCheckerSession & session, const protocol::PoseStamped & pose);
  std::optional<protocol::TwistStamped> take_compute(
    ControllerSession & session, const protocol::PoseStamped & pose,
    const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker);

  // Calls answered from a carried reply, and calls that went on their own after all.
  std::uint64_t carried_used() const;
  std::uint64_t sent_alone() const;

private:
  struct PendingCheck
  {
    const PluginSession * session{nullptr};
    Carried carried;
    std::optional<protocol::Bytes> reply;
  };
  struct PendingCompute
  {
    const PluginSession * session{nullptr};
    PreparedCommand prepared;
    std::optional<protocol::Bytes> reply;
  };

  mutable std::mutex mutex_;
  ControllerSession * controller_{nullptr};
  ProgressCheckerSession * progress_checker_{nullptr};
  // The goal check's velocity and tolerances: the command's inputs besides the pose.
  struct CommandInputs
  {
    std::array<double, 6> velocity{};
    std::optional<protocol::GoalChecker> tolerances;
  };

  std::optional<PendingCheck> check_;
  std::optional<PendingCompute> compute_;
  std::optional<CommandInputs> command_inputs_;  // this cycle's, until the progress check
  std::uint64_t carried_used_{0};
  std::uint64_t sent_alone_{0};
};

}  // namespace nav2_pyif_bridge::client
