// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// The operations of the protocol and their wire names (the request's `op`, also the last chunk of
// the Zenoh key `P/rpc/<op>`), and each op's traits.

#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>

#include "nav2_pyif_bridge/protocol/nav2_errors.hpp"

namespace nav2_pyif_bridge::protocol
{

// The enumerator order is also the order of the alternatives of RequestBody and ReplyBody
// (bodies.hpp), so a body's variant index *is* its op.
enum class Op : std::uint8_t
{
  Configure,  // every plugin type
  Activate,  // every plugin type
  Deactivate,  // every plugin type
  Cleanup,  // every plugin type
  SetParameters,  // every plugin type
  SetPlan,  // controller and path_handler
  ComputeVelocityCommands,  // controller
  SetSpeedLimit,  // controller
  Cancel,  // controller
  Reset,  // controller and goal_checker and progress_checker and costmap_layer
  CreatePlan,  // global_planner
  CancelPlan,  // global_planner
  Smooth,  // smoother
  IsGoalReached,  // goal_checker
  GetTolerances,  // goal_checker
  Check,  // progress_checker
  UpdateBounds,  // costmap_layer
  UpdateCosts,  // costmap_layer
  MatchSize,  // costmap_layer
  OnRun,  // behavior
  OnCycleUpdate,  // behavior
  OnActionCompletion,  // behavior
  FindPlanSegment,  // path_handler
};

inline constexpr std::size_t kOpCount = 23;

inline constexpr std::array<std::string_view, kOpCount> kOpNames = {
  "configure",
  "activate",
  "deactivate",
  "cleanup",
  "set_parameters",
  "set_plan",
  "compute_velocity_commands",
  "set_speed_limit",
  "cancel",
  "reset",
  "create_plan",
  "cancel_plan",
  "smooth",
  "is_goal_reached",
  "get_tolerances",
  "check",
  "update_bounds",
  "update_costs",
  "match_size",
  "on_run",
  "on_cycle_update",
  "on_action_completion",
  "find_plan_segment",
};

constexpr std::string_view op_name(Op op) noexcept
{
  return kOpNames[static_cast<std::size_t>(op)];
}

// Which of a plugin's timeouts bounds each op's reply (schema.py OP_TIMEOUT; PROTOCOL.md section
// 8).
enum class TimeoutClass : std::uint8_t
{
  Call,
  Lifecycle,
  Configure,
  Plan,
};

inline constexpr std::array<TimeoutClass, kOpCount> kOpTimeout = {
  TimeoutClass::Configure,  // configure
  TimeoutClass::Lifecycle,  // activate
  TimeoutClass::Lifecycle,  // deactivate
  TimeoutClass::Lifecycle,  // cleanup
  TimeoutClass::Lifecycle,  // set_parameters
  TimeoutClass::Call,  // set_plan
  TimeoutClass::Call,  // compute_velocity_commands
  TimeoutClass::Call,  // set_speed_limit
  TimeoutClass::Call,  // cancel
  TimeoutClass::Call,  // reset
  TimeoutClass::Plan,  // create_plan
  TimeoutClass::Lifecycle,  // cancel_plan
  TimeoutClass::Plan,  // smooth
  TimeoutClass::Call,  // is_goal_reached
  TimeoutClass::Call,  // get_tolerances
  TimeoutClass::Call,  // check
  TimeoutClass::Call,  // update_bounds
  TimeoutClass::Call,  // update_costs
  TimeoutClass::Call,  // match_size
  TimeoutClass::Lifecycle,  // on_run
  TimeoutClass::Call,  // on_cycle_update
  TimeoutClass::Lifecycle,  // on_action_completion
  TimeoutClass::Call,  // find_plan_segment
};

constexpr TimeoutClass timeout_class(Op op) noexcept
{
  return kOpTimeout[static_cast<std::size_t>(op)];
}

// smooth gives the smoother max_time: the reply is awaited that long and this much more [s], or the
// plan timeout when that is longer (schema.py SMOOTH_GRACE_S).
inline constexpr double kSmoothGraceS = 1.0;

// Whether each op's request carries the plugin's costmap (schema.py COSTMAP_SENT, from the
// request's costmap field; PROTOCOL.md section 5).
enum class CostmapSent : std::uint8_t
{
  Never,
  IfChanged,
  Always,
};

inline constexpr std::array<CostmapSent, kOpCount> kOpCostmap = {
  CostmapSent::Always,  // configure
  CostmapSent::Never,  // activate
  CostmapSent::Never,  // deactivate
  CostmapSent::Never,  // cleanup
  CostmapSent::Never,  // set_parameters
  CostmapSent::Never,  // set_plan
  CostmapSent::IfChanged,  // compute_velocity_commands
  CostmapSent::Never,  // set_speed_limit
  CostmapSent::Never,  // cancel
  CostmapSent::Never,  // reset
  CostmapSent::IfChanged,  // create_plan
  CostmapSent::Never,  // cancel_plan
  CostmapSent::IfChanged,  // smooth
  CostmapSent::Never,  // is_goal_reached
  CostmapSent::Never,  // get_tolerances
  CostmapSent::Never,  // check
  CostmapSent::Never,  // update_bounds
  CostmapSent::Never,  // update_costs
  CostmapSent::Never,  // match_size
  CostmapSent::IfChanged,  // on_run
  CostmapSent::IfChanged,  // on_cycle_update
  CostmapSent::Never,  // on_action_completion
  CostmapSent::Never,  // find_plan_segment
};

constexpr CostmapSent costmap_sent(Op op) noexcept
{
  return kOpCostmap[static_cast<std::size_t>(op)];
}

// What a new session on the host is sent again after configure (and activate), per plugin type, in
// this order (schema.py RESTORED; PROTOCOL.md section 4).
inline constexpr std::array<std::pair<PluginKind, Op>, 4> kRestored = {{
  {PluginKind::Controller, Op::SetPlan},
  {PluginKind::Controller, Op::SetSpeedLimit},
  {PluginKind::Behavior, Op::OnRun},
  {PluginKind::PathHandler, Op::SetPlan},
}};

// Whether a plugin type sends or answers a call of the carried control cycle (schema.py CARRIES;
// PROTOCOL.md section 15): the plugins of such types in one controller_server share its carried
// cycle.
constexpr bool in_carried_cycle(PluginKind kind) noexcept
{
  return kind == PluginKind::Controller ||
         kind == PluginKind::GoalChecker ||
         kind == PluginKind::ProgressChecker ||
         kind == PluginKind::PathHandler;
}

// std::nullopt for a name this version of the protocol does not know.
constexpr std::optional<Op> op_from_name(std::string_view name) noexcept
{
  for (std::size_t i = 0; i < kOpCount; ++i) {
    if (kOpNames[i] == name) {
      return static_cast<Op>(i);
    }
  }
  return std::nullopt;
}

}  // namespace nav2_pyif_bridge::protocol
