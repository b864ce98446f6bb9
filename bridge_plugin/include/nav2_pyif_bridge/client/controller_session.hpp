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
#include <utility>
#include <vector>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

// What a cycle's request carries of the session's state, acknowledged by its ok reply.
struct Attached
{
  std::vector<std::pair<std::string, std::uint64_t>> inputs;  // name, generation
  bool plan{false};  // the plan follow() remembered (Lyrical)
  bool goal{false};  // and its global goal
};

// The command and the encoded replies of the calls its query carried (those that ran).
struct CommandReplies
{
  protocol::TwistStamped cmd_vel;
  std::vector<protocol::CarriedCall> carried;
};

class ControllerSession : public KindSession<PluginKind::Controller>
{
public:
  using KindSession::KindSession;

  // The plan in the costmap's global frame, remembered for re-sending. std::nullopt when the
  // host has it. When the host failed the call (CallError::host_failed) the plan is kept as
  // owed and the failure returned, not thrown: the next cycle sends the plan first, as does a
  // re-established session. Nav2's behaviour tree replans about once a second, and a throw
  // here would end FollowPath at once, where a failing cycle gets the controller server's
  // failure_tolerance. The planner's own errors (InvalidPath, ...) throw.
  std::optional<CallError> set_plan(const protocol::Path & path);
  // Lyrical: the plan controller_server transformed and pruned for this cycle, and its global
  // goal, both in the costmap's global frame. Remembered as set_plan's plan is (a
  // re-established session gets both with set_plan), and carried by the next cycle's request
  // only when they changed since the host last got them (their stamps aside, which move every
  // cycle). Sends nothing itself. From then on no command is prepared for another call's query
  // to carry: Nav2 transforms the cycle's plan after the goal check, so a command prepared
  // there would run on the last cycle's plan (and the planner would compute twice).
  void follow(const protocol::Path & plan, const protocol::PoseStamped & goal);
  // The latest message of an input topic (from a subscription's thread): sent with the next
  // control cycle, once; every input again after the host lost the session.
  void set_input(protocol::Input input);
  // The debug outputs someone subscribes to, asked for in every following cycle.
  void set_debug_wanted(std::vector<std::string> names);
  // The debug outputs the last successful cycle returned (moved out).
  std::vector<protocol::DebugOutput> take_debug();

  // The command, every component finite (else NoValidControl). The costmap travels when it
  // changed since the host last got it, and so do the inputs. The query carries `carry`, the
  // calls that follow it in the cycle (the goal check, when controller_server calls it last).
  CommandReplies compute_velocity_commands(
    const protocol::PoseStamped & pose, const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker,
    std::vector<protocol::CarriedCall> carry = {});
  // The same call prepared for another plugin's query to carry (PROTOCOL.md section 15);
  // std::nullopt when the session cannot prepare one now.
  std::optional<Carried> prepare_command(
    const protocol::PoseStamped & pose, const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker);
  // The command from the carried reply, when Nav2's call is the prepared one
  // (PluginSession::take: it attaches what the prepared one did) and no plan is owed; else
  // std::nullopt, and the call goes on its own. Errors throw as compute_velocity_commands.
  std::optional<protocol::TwistStamped> take_command(
    Carried prepared, const std::optional<protocol::Bytes> & reply,
    const protocol::PoseStamped & pose, const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker);
  // Remembered after an ok reply, and also when the host failed the call (none alive, no
  // reply in time, Unavailable), so a host that comes back drives at the latest limit; one
  // the planner refused is not (as the reference client).
  void set_speed_limit(double speed_limit, bool percentage);

  bool has_plan() const;

protected:
  std::optional<protocol::RequestBody> restored(protocol::Op op) override;
  void forget_state() override;

private:
  // The request body of a cycle (inputs not yet acknowledged attached, with their generations).
  protocol::ComputeVelocityCommandsRequest command_body(
    const protocol::PoseStamped & pose, const std::array<double, 6> & velocity,
    const std::optional<protocol::GoalChecker> & goal_checker, Attached & attached);
  // The reply's command, checked; what was attached acknowledged, the debug outputs kept.
  protocol::TwistStamped command_of(
    protocol::ComputeVelocityCommandsReply reply, const Attached & attached);

  // Sends plan_; it is no longer owed once the host has it.
  void send_plan();

  std::optional<protocol::Path> plan_;
  bool plan_owed_{false};  // set_plan failed on the host: sent before the next cycle
  // Lyrical (follow): the global goal, and what of plan_ and goal_ the host has not had yet.
  std::optional<protocol::PoseStamped> goal_;
  bool plan_unsent_{false};
  bool goal_unsent_{false};
  bool follows_cycle_plan_{false};
  std::optional<protocol::SetSpeedLimitRequest> speed_limit_;

  // The latest message of each input; `sent` is the generation the host acknowledged, in
  // the session of `sent_epoch`: a new session (a host restart, another replica, a new
  // configure) has none of them, so every input goes again with the next cycle.
  struct LatestInput
  {
    protocol::Input input;
    std::uint64_t generation{0};
    std::uint64_t sent{0};
    std::uint64_t sent_epoch{0};
  };
  // Its own lock: subscription callbacks must not wait for a control cycle's round trip.
  mutable std::mutex inputs_mutex_;
  std::map<std::string, LatestInput> inputs_;
  std::vector<std::string> debug_wanted_;
  std::vector<protocol::DebugOutput> debug_;
};

}  // namespace nav2_pyif_bridge::client
