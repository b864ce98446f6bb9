// The operation-specific bodies of requests and replies (PROTOCOL.md section 13,
// "Operations"). Ops with an empty body still get their own (empty) type, so that a body's
// type alone says which op it belongs to.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include "nav2_pyif_bridge/protocol/ops.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::protocol
{

// --- lifecycle ------------------------------------------------------------------------------

struct ConfigureRequest
{
  std::string plugin_type;  // "controller" or "global_planner"
  std::string name;         // plugin name in Nav2, e.g. FollowPath
  std::string node;         // name of the Nav2 server node
  Params params;            // every parameter under the plugin's namespace, prefix stripped
  std::string global_frame;
  std::string robot_base_frame;
  Costmap costmap;  // always sent with configure
};
struct ConfigureReply
{
  Params declared;  // parameters the planner declared, with their current values
};

struct ActivateRequest {};
struct ActivateReply {};
struct DeactivateRequest {};
struct DeactivateReply {};
struct CleanupRequest {};
struct CleanupReply {};

struct SetParametersRequest
{
  Params params;  // changed parameters
};
struct SetParametersReply
{
  StringMap rejected;  // name -> reason, for each change not applied
};

// --- controller -----------------------------------------------------------------------------

struct SetPlanRequest
{
  Path path;  // in the costmap's global frame
};
struct SetPlanReply {};

struct ComputeVelocityCommandsRequest
{
  PoseStamped pose;                         // robot pose, in the costmap's global frame
  std::array<double, 6> velocity{};         // in the robot base frame
  std::optional<GoalChecker> goal_checker;  // when Nav2 gave a goal checker
  std::optional<Costmap> costmap;           // only when changed since the host last got it
};
struct ComputeVelocityCommandsReply
{
  TwistStamped cmd_vel;
};

struct SetSpeedLimitRequest
{
  double speed_limit{0.0};  // m/s, or percent of the maximum when percentage
  bool percentage{false};
};
struct SetSpeedLimitReply {};

struct CancelRequest {};
struct CancelReply
{
  bool cancelled{false};  // true when the controller finished cancelling
};

struct ResetRequest {};
struct ResetReply {};

// --- global planner -------------------------------------------------------------------------

struct CreatePlanRequest
{
  PoseStamped start;               // in the costmap's global frame
  PoseStamped goal;                // in the costmap's global frame
  std::optional<Costmap> costmap;  // only when changed since the host last got it
};
struct CreatePlanReply
{
  Path path;
};

struct CancelPlanRequest
{
  std::uint64_t target_seq{0};  // seq of the create_plan call to cancel
};
struct CancelPlanReply
{
  bool accepted{false};  // true when that call was running and is now flagged
};

// --- one type per direction -----------------------------------------------------------------

// Alternative i belongs to Op(i); the static_asserts below keep that true.
using RequestBody = std::variant<
  ConfigureRequest, ActivateRequest, DeactivateRequest, CleanupRequest, SetParametersRequest,
  SetPlanRequest, ComputeVelocityCommandsRequest, SetSpeedLimitRequest, CancelRequest,
  ResetRequest, CreatePlanRequest, CancelPlanRequest>;

using ReplyBody = std::variant<
  ConfigureReply, ActivateReply, DeactivateReply, CleanupReply, SetParametersReply,
  SetPlanReply, ComputeVelocityCommandsReply, SetSpeedLimitReply, CancelReply, ResetReply,
  CreatePlanReply, CancelPlanReply>;

inline Op op_of(const RequestBody & body) noexcept {return static_cast<Op>(body.index());}
inline Op op_of(const ReplyBody & body) noexcept {return static_cast<Op>(body.index());}

namespace detail
{
template<Op op, class Request, class Reply>
constexpr bool matches()
{
  constexpr auto i = static_cast<std::size_t>(op);
  return std::is_same_v<std::variant_alternative_t<i, RequestBody>, Request>&&
         std::is_same_v<std::variant_alternative_t<i, ReplyBody>, Reply>;
}
}  // namespace detail

static_assert(std::variant_size_v<RequestBody> == kOpCount);
static_assert(std::variant_size_v<ReplyBody> == kOpCount);
static_assert(detail::matches<Op::Configure, ConfigureRequest, ConfigureReply>());
static_assert(detail::matches<Op::Activate, ActivateRequest, ActivateReply>());
static_assert(detail::matches<Op::Deactivate, DeactivateRequest, DeactivateReply>());
static_assert(detail::matches<Op::Cleanup, CleanupRequest, CleanupReply>());
static_assert(detail::matches<Op::SetParameters, SetParametersRequest, SetParametersReply>());
static_assert(detail::matches<Op::SetPlan, SetPlanRequest, SetPlanReply>());
static_assert(
  detail::matches<Op::ComputeVelocityCommands, ComputeVelocityCommandsRequest,
  ComputeVelocityCommandsReply>());
static_assert(detail::matches<Op::SetSpeedLimit, SetSpeedLimitRequest, SetSpeedLimitReply>());
static_assert(detail::matches<Op::Cancel, CancelRequest, CancelReply>());
static_assert(detail::matches<Op::Reset, ResetRequest, ResetReply>());
static_assert(detail::matches<Op::CreatePlan, CreatePlanRequest, CreatePlanReply>());
static_assert(detail::matches<Op::CancelPlan, CancelPlanRequest, CancelPlanReply>());

}  // namespace nav2_pyif_bridge::protocol
