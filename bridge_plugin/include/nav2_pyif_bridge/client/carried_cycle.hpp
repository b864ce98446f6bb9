// PROTOCOL.md section 15 on the plugin side: in one controller_server, a call of the control
// cycle carries the calls of the Python plugins that follow it, prepared for the same pose
// and velocity. controller_server calls them in one of two orders:
// - goal check first (Jazzy from 1.3.13, Kilted): the goal check's query carries the
//   progress check and the command: one round trip per cycle;
// - goal check last (Humble, Jazzy 1.3.8 to 1.3.12): the progress check goes on its own, and
//   the command's query carries the goal check, for the goal the goal checker was last
//   given: two round trips (one without a Python progress checker).
// The order is learned from the calls (as the reference client's ControlCycle): a goal check
// with the pose and velocity of the command before it says "last", a command with those of
// the goal check before it says "first"; a robot standing still says neither. A prepared
// call's reply is used only when Nav2's call is the prepared one (PluginSession::take);
// otherwise the call goes on its own, so the outcome is always that of Nav2's order.
//
// Nav2 does not tell a goal checker which controller and progress checker it calls next: the
// cycle holds the controller that got the latest plan and the progress checker reset last
// (controller_server resets the current one at every new goal). A wrong guess costs one
// prepared call the host runs and nobody uses.
//
// Lyrical calls its path handler's findPlanSegment between the check and the command, with the
// check's pose (PROTOCOL.md section 19): a Python path handler's segment is prepared like the
// command and carried by the goal check's (or, TF moved on, the check's) query. The cycle
// holds the path handler that got the latest plan. Lyrical's command needs the segment's plan,
// so it is not carried there: two round trips a cycle, with or without a Python path handler.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/client/path_handler_session.hpp"

namespace nav2_pyif_bridge::client
{

// The encoded requests a call's query carries for other keys, or the encoded replies of
// those that ran, in order (PROTOCOL.md section 15).
using CarriedCalls = std::vector<protocol::CarriedCall>;

// Nav2's goal check (pose and goal in the costmap's global frame, velocity in the robot's) and
// progress check, as the requests the cycle takes.
inline protocol::IsGoalReachedRequest goal_check(
  const std::array<double, 7> & pose, const std::array<double, 7> & goal,
  const std::array<double, 6> & velocity)
{
  return {pose, goal, velocity, std::nullopt, std::nullopt};
}
inline protocol::CheckRequest progress_check(const protocol::PoseStamped & pose)
{
  return {pose, std::nullopt};
}

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
  void use_path_handler(PathHandlerSession & session);
  void forget(const PluginSession & session);

  // Nav2's three calls. `robot`: the goal checker's own lookup of the robot's pose when it
  // gives Nav2's pose (the stamped message the other calls then get, when TF has not moved
  // on); without it the goal check carries nothing. `tolerances`: what the controller will
  // be given.
  bool is_goal_reached(
    GoalCheckerSession & checker, const std::optional<protocol::PoseStamped> & robot,
    const protocol::IsGoalReachedRequest & request,
    const std::optional<protocol::GoalChecker> & tolerances);
  bool check(ProgressCheckerSession & session, const protocol::CheckRequest & request);
  // The path handler's segment (Lyrical), answered from the checks' query when prepared for
  // this pose.
  std::pair<std::size_t, std::size_t> find_plan_segment(
    PathHandlerSession & session, const protocol::PoseStamped & pose);
  protocol::TwistStamped compute_velocity_commands(
    ControllerSession & session, const protocol::PoseStamped & pose,
    const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker);

  // Calls answered from a carried reply; whether the goal check was found to end the cycle.
  std::uint64_t carried_used() const;
  bool goal_last() const;

private:
  // A call prepared for `session`, and the reply its carrier's query brought back.
  struct Pending
  {
    const PluginSession * session{nullptr};
    Carried prepared;
    std::optional<protocol::Bytes> reply;
  };
  // The goal check's inputs, for the command the check carries when TF moved on (goal first).
  struct CommandInputs
  {
    protocol::PoseStamped pose;
    std::array<double, 6> velocity{};
    std::optional<protocol::GoalChecker> tolerances;
  };
  using Seen = std::pair<std::array<double, 7>, std::array<double, 6>>;  // pose, velocity

  // Evidence of the order; switches when one cycle fits one order and not the other.
  void learn(bool goal_last_seen, bool seen);
  // The pending call prepared for `session`, taken out of `slot`.
  static std::optional<Pending> take_for(
    std::optional<Pending> & slot, const PluginSession & session);
  // The calls after the check, prepared for `pose` into `carry` (mutex_ held): the path
  // handler's segment when there is one (Lyrical), else the command.
  void prepare_rest(
    CarriedCalls & carry, const protocol::PoseStamped & pose, const CommandInputs & inputs,
    std::optional<Pending> & segment, std::optional<Pending> & compute);
  // A prepared call joins `carry`, and waits for its reply.
  static std::optional<Pending> add(
    CarriedCalls & carry, const PluginSession & session, std::optional<Carried> prepared);
  // The carried replies of a carrier's query, handed to the pending calls prepared for it.
  void keep(
    std::optional<Pending> & slot, std::optional<Pending> pending, CarriedCalls & replies,
    std::size_t & next, const PluginSession * current);
  void count(bool carried);

  mutable std::mutex mutex_;
  ControllerSession * controller_{nullptr};
  ProgressCheckerSession * progress_checker_{nullptr};
  PathHandlerSession * path_handler_{nullptr};
  GoalCheckerSession * goal_checker_{nullptr};  // the one Nav2 called last
  std::optional<Pending> check_;
  std::optional<Pending> segment_;
  std::optional<Pending> compute_;
  std::optional<Pending> goal_check_;
  std::optional<CommandInputs> command_inputs_;  // this cycle's, until the progress check
  bool goal_last_{false};
  bool seen_first_{false};
  bool seen_last_{false};
  std::optional<Seen> last_goal_check_;
  std::optional<Seen> last_command_;
  std::optional<std::array<double, 7>> goal_;  // the goal checker's last goal
  std::uint64_t goal_seq_{0};  // the goal checker's seq after that call: reset since?
  std::uint64_t carried_used_{0};
};

}  // namespace nav2_pyif_bridge::client
