// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// The operation-specific bodies of requests and replies (PROTOCOL.md section 13, "Operations"). Ops
// with an empty body still get their own (empty) type, so that a body's type alone says which op it
// belongs to.

#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "nav2_pyif_bridge/protocol/ops.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::protocol
{

// --- configure -----------------------------------------------------------------------------------
struct ConfigureRequest
{
  // 'controller', 'global_planner', 'smoother', 'goal_checker', 'progress_checker',
  // 'costmap_layer', 'behavior' or 'path_handler'
  std::string plugin_type;
  // plugin name in Nav2 (e.g. FollowPath)
  std::string name;
  // name of the Nav2 server node
  std::string node;
  // every parameter under the plugin's namespace, prefix stripped
  Params params;
  // the costmap's global frame (a behaviour's: behavior_server's local_frame)
  std::string global_frame;
  // the robot base frame
  std::string robot_base_frame;
  // the costmap at configure time (0 x 0 when the plugin has none: a progress checker, a smoother
  // before its costmap subscription delivered one)
  Costmap costmap;
  // optional: Nav2's parameters outside the plugin's namespace that a planner may need, by their
  // Nav2 names: controller_frequency [Hz] (controller_server's), inflation_radius [m] and
  // cost_scaling_factor [1/m] (the costmap's inflation layer); absent when none is known
  std::optional<Params> nav2_params;
};

struct ConfigureReply
{
  // parameters the planner declared, with current values
  Params declared;
  // optional: what the host serves on this key, e.g. pkg.module:Class (for logs and reports; older
  // hosts leave it out)
  std::optional<std::string> planner;
  // optional: given parameters the planner does not declare (ignored), name -> reason; absent when
  // none
  std::optional<StringMap> undeclared;
  // optional: debug outputs the planner may return, name -> ROS message type; absent when none
  std::optional<StringMap> debug_outputs;
};

// --- activate ------------------------------------------------------------------------------------
struct ActivateRequest {};

struct ActivateReply {};

// --- deactivate ----------------------------------------------------------------------------------
struct DeactivateRequest {};

struct DeactivateReply {};

// --- cleanup -------------------------------------------------------------------------------------
struct CleanupRequest {};

struct CleanupReply {};

// --- set_parameters ------------------------------------------------------------------------------
struct SetParametersRequest
{
  // changed parameters
  Params params;
};

struct SetParametersReply
{
  // name -> reason, for each change not applied
  StringMap rejected;
};

// --- set_plan ------------------------------------------------------------------------------------
struct SetPlanRequest
{
  // the plan to follow, in the costmap's global frame (section 14); a path handler's, to cut
  // segments from, in its own frame (section 19)
  Path path;
  // optional: the global goal, same frame: Nav2's (Lyrical); absent: the plan's last pose
  std::optional<PoseStamped> goal;
};

struct SetPlanReply {};

// --- compute_velocity_commands -------------------------------------------------------------------
struct ComputeVelocityCommandsRequest
{
  // robot pose, in the costmap's global frame
  PoseStamped pose;
  // current velocity in the robot base frame
  std::array<double, 6> velocity{};
  // optional: tolerances, when Nav2 gave a goal checker
  std::optional<GoalChecker> goal_checker;
  // optional: present only when changed since last sent
  std::optional<Costmap> costmap;
  // optional: the plan Nav2 transformed for this cycle, costmap's global frame (Lyrical); present
  // only when it changed since the host last got it
  std::optional<Path> plan;
  // optional: the global goal, same frame (Lyrical); present only when it changed since the host
  // last got it
  std::optional<PoseStamped> goal;
  // optional: input messages received since the last call (the latest of each); absent when none
  std::optional<std::vector<Input>> inputs;
  // optional: names of the debug outputs someone subscribes to; absent when none
  std::optional<std::vector<std::string>> debug_wanted;
  // optional: calls to run after this one, in order, as far as Nav2 would go; absent when none
  std::optional<std::vector<CarriedCall>> carry;
};

struct ComputeVelocityCommandsReply
{
  // the command; every component finite
  TwistStamped cmd_vel;
  // optional: debug outputs among debug_wanted the planner returned; absent when none
  std::optional<std::vector<DebugOutput>> debug;
  // optional: the replies of the carried calls that ran, in order; absent when none ran
  std::optional<std::vector<CarriedCall>> carried;
};

// --- set_speed_limit -----------------------------------------------------------------------------
struct SetSpeedLimitRequest
{
  // m/s, or percent of the maximum when percentage
  double speed_limit{0.0};
  // speed_limit is a percentage
  bool percentage{false};
};

struct SetSpeedLimitReply {};

// --- cancel --------------------------------------------------------------------------------------
struct CancelRequest {};

struct CancelReply
{
  // true when the controller finished cancelling
  bool cancelled{false};
};

// --- reset ---------------------------------------------------------------------------------------
struct ResetRequest {};

struct ResetReply {};

// --- create_plan ---------------------------------------------------------------------------------
struct CreatePlanRequest
{
  // start pose, in the costmap's global frame
  PoseStamped start;
  // goal pose, in the costmap's global frame
  PoseStamped goal;
  // optional: present only when changed since last sent
  std::optional<Costmap> costmap;
  // optional: poses to pass through, in order, same frame (Lyrical); absent when none
  std::optional<Path> viapoints;
};

struct CreatePlanReply
{
  // the plan; every value finite
  Path path;
};

// --- cancel_plan ---------------------------------------------------------------------------------
struct CancelPlanRequest
{
  // seq of the create_plan call to cancel
  std::uint64_t target_seq{0};
};

struct CancelPlanReply
{
  // true when that call was running and is now flagged
  bool accepted{false};
};

// --- smooth --------------------------------------------------------------------------------------
struct SmoothRequest
{
  // the path to smooth, in its own frame (Nav2 does not transform it)
  Path path;
  // time the smoother may take [s] (SmoothPath's max_smoothing_duration)
  double max_time{0.0};
  // optional: present only when changed since last sent
  std::optional<Costmap> costmap;
};

struct SmoothReply
{
  // the smoothed path, same frame; every value finite
  Path path;
  // smooth()'s return: false when it stopped at max_time
  bool was_completed{false};
};

// --- is_goal_reached -----------------------------------------------------------------------------
struct IsGoalReachedRequest
{
  // robot pose (x, y, z, qx, qy, qz, qw), the costmap's global frame
  std::array<double, 7> pose{};
  // goal pose, same frame
  std::array<double, 7> goal{};
  // current velocity in the robot base frame
  std::array<double, 6> velocity{};
  // optional: true: isGoalXYReached, the position only (Lyrical); absent: isGoalReached
  std::optional<bool> xy_only;
  // optional: calls to run after this one, in order, as far as Nav2 would go; absent when none
  std::optional<std::vector<CarriedCall>> carry;
};

struct IsGoalReachedReply
{
  // the goal is reached
  bool reached{false};
  // optional: the replies of the carried calls that ran, in order; absent when none ran
  std::optional<std::vector<CarriedCall>> carried;
};

// --- get_tolerances ------------------------------------------------------------------------------
struct GetTolerancesRequest {};

struct GetTolerancesReply
{
  // getTolerances' return: false when the checker has none
  bool available{false};
  // x, y, z [m], qx, qy, qz, qw: the yaw tolerance as a quaternion
  std::array<double, 7> pose_tolerance{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  // vx, vy, vz [m/s], wx, wy, wz [rad/s]
  std::array<double, 6> velocity_tolerance{};
  // optional: [m] (Lyrical's getTolerances); absent when the checker has none
  std::optional<double> path_length_tolerance;
};

// --- check ---------------------------------------------------------------------------------------
struct CheckRequest
{
  // robot pose, in the costmap's global frame
  PoseStamped pose;
  // optional: calls to run after this one, in order, as far as Nav2 would go; absent when none
  std::optional<std::vector<CarriedCall>> carry;
};

struct CheckReply
{
  // check()'s return: false = failed to make progress
  bool making_progress{false};
  // optional: the replies of the carried calls that ran, in order; absent when none ran
  std::optional<std::vector<CarriedCall>> carried;
};

// --- update_bounds -------------------------------------------------------------------------------
struct UpdateBoundsRequest
{
  // robot x in the costmap's global frame [m]
  double robot_x{0.0};
  // robot y [m]
  double robot_y{0.0};
  // robot yaw [rad]
  double robot_yaw{0.0};
  // the bounds so far (earlier layers'), world [m]
  double min_x{0.0};
  // [m]
  double min_y{0.0};
  // [m]
  double max_x{0.0};
  // [m]
  double max_y{0.0};
};

struct UpdateBoundsReply
{
  // the bounds grown to cover what this layer will change [m]
  double min_x{0.0};
  // [m]
  double min_y{0.0};
  // [m]
  double max_x{0.0};
  // [m]
  double max_y{0.0};
};

// --- update_costs --------------------------------------------------------------------------------
struct UpdateCostsRequest
{
  // the window to update: first cell column of the master grid
  std::int64_t min_i{0};
  // first cell row
  std::int64_t min_j{0};
  // one past the last column
  std::int64_t max_i{0};
  // one past the last row
  std::int64_t max_j{0};
  // the master grid's origin (cell (0, 0)'s corner) [m]
  double origin_x{0.0};
  // [m]
  double origin_y{0.0};
  // m per cell
  double resolution{0.0};
};

struct UpdateCostsReply
{
  // max_i - min_i
  std::uint32_t width{0};
  // max_j - min_j
  std::uint32_t height{0};
  // height * width uint8 costs of the window, row-major from (min_i, min_j)
  std::vector<std::uint8_t> costs;
  // how they meet the master's: max, max_keep_unknown, overwrite, true_overwrite
  std::string combine;
};

// --- match_size ----------------------------------------------------------------------------------
struct MatchSizeRequest
{
  // the master grid's cells along x
  std::uint32_t size_x{0};
  // cells along y
  std::uint32_t size_y{0};
  // m per cell
  double resolution{0.0};
  // cell (0, 0)'s corner [m]
  double origin_x{0.0};
  // [m]
  double origin_y{0.0};
};

struct MatchSizeReply {};

// --- on_run --------------------------------------------------------------------------------------
struct OnRunRequest
{
  // the action type, e.g. nav2_msgs/action/BackUp
  std::string action;
  // the goal's fields as plain values (section 17), e.g. target_x [m], speed [m/s], time_allowance
  // [s]
  Params command;
  // robot pose, in behavior_server's local frame
  PoseStamped pose;
  // optional: the local costmap, present only when changed
  std::optional<Costmap> costmap;
};

struct OnRunReply
{
  // 'succeeded', 'failed' or 'running' (on_run: not 'running')
  std::string status;
  // why it failed, mapped to the action's error code: '' (none), 'unknown', 'timeout', 'tf_error',
  // 'invalid_input', 'collision_ahead'
  std::string failure;
};

// --- on_cycle_update -----------------------------------------------------------------------------
struct OnCycleUpdateRequest
{
  // robot pose, in behavior_server's local frame
  PoseStamped pose;
  // time since on_run succeeded [s]
  double elapsed{0.0};
  // optional: the local costmap, present only when changed
  std::optional<Costmap> costmap;
};

struct OnCycleUpdateReply
{
  // 'succeeded', 'failed' or 'running' (on_run: not 'running')
  std::string status;
  // why it failed, mapped to the action's error code: '' (none), 'unknown', 'timeout', 'tf_error',
  // 'invalid_input', 'collision_ahead'
  std::string failure;
  // optional: the command to publish this cycle; every component finite; absent: none (the plugin
  // stops the robot when the status is not 'running')
  std::optional<TwistStamped> cmd_vel;
  // optional: the action's feedback fields, e.g. distance_traveled [m]; absent when none
  std::optional<Params> feedback;
};

// --- on_action_completion ------------------------------------------------------------------------
struct OnActionCompletionRequest
{
  // how the action ended: 'succeeded', 'failed' or 'cancelled'
  std::string status;
  // the action's total_elapsed_time [s]
  double elapsed{0.0};
};

struct OnActionCompletionReply {};

// --- find_plan_segment ---------------------------------------------------------------------------
struct FindPlanSegmentRequest
{
  // robot pose, in the plan's frame
  PoseStamped pose;
};

struct FindPlanSegmentReply
{
  // first pose of the segment: an index into the plan set_plan sent
  std::uint64_t start{0};
  // one past its last pose; start < end <= the plan's length
  std::uint64_t end{0};
};

// Alternative i belongs to Op(i).
using RequestBody = std::variant<ConfigureRequest, ActivateRequest, DeactivateRequest,
  CleanupRequest, SetParametersRequest, SetPlanRequest, ComputeVelocityCommandsRequest,
  SetSpeedLimitRequest, CancelRequest, ResetRequest, CreatePlanRequest, CancelPlanRequest,
  SmoothRequest, IsGoalReachedRequest, GetTolerancesRequest, CheckRequest, UpdateBoundsRequest,
  UpdateCostsRequest, MatchSizeRequest, OnRunRequest, OnCycleUpdateRequest,
  OnActionCompletionRequest, FindPlanSegmentRequest>;

// Alternative i belongs to Op(i).
using ReplyBody = std::variant<ConfigureReply, ActivateReply, DeactivateReply, CleanupReply,
  SetParametersReply, SetPlanReply, ComputeVelocityCommandsReply, SetSpeedLimitReply, CancelReply,
  ResetReply, CreatePlanReply, CancelPlanReply, SmoothReply, IsGoalReachedReply, GetTolerancesReply,
  CheckReply, UpdateBoundsReply, UpdateCostsReply, MatchSizeReply, OnRunReply, OnCycleUpdateReply,
  OnActionCompletionReply, FindPlanSegmentReply>;

inline Op op_of(const RequestBody & body) noexcept {return static_cast<Op>(body.index());}
inline Op op_of(const ReplyBody & body) noexcept {return static_cast<Op>(body.index());}

static_assert(std::variant_size_v<RequestBody> == kOpCount);
static_assert(std::variant_size_v<ReplyBody> == kOpCount);

// The reply body of each request body: ReplyOf<SmoothRequest> is SmoothReply.
template<class Request>
struct ReplyOfT;
template<> struct ReplyOfT<ConfigureRequest>
{using type = ConfigureReply;};
template<> struct ReplyOfT<ActivateRequest>
{using type = ActivateReply;};
template<> struct ReplyOfT<DeactivateRequest>
{using type = DeactivateReply;};
template<> struct ReplyOfT<CleanupRequest>
{using type = CleanupReply;};
template<> struct ReplyOfT<SetParametersRequest>
{using type = SetParametersReply;};
template<> struct ReplyOfT<SetPlanRequest>
{using type = SetPlanReply;};
template<> struct ReplyOfT<ComputeVelocityCommandsRequest>
{using type = ComputeVelocityCommandsReply;};
template<> struct ReplyOfT<SetSpeedLimitRequest>
{using type = SetSpeedLimitReply;};
template<> struct ReplyOfT<CancelRequest>
{using type = CancelReply;};
template<> struct ReplyOfT<ResetRequest>
{using type = ResetReply;};
template<> struct ReplyOfT<CreatePlanRequest>
{using type = CreatePlanReply;};
template<> struct ReplyOfT<CancelPlanRequest>
{using type = CancelPlanReply;};
template<> struct ReplyOfT<SmoothRequest>
{using type = SmoothReply;};
template<> struct ReplyOfT<IsGoalReachedRequest>
{using type = IsGoalReachedReply;};
template<> struct ReplyOfT<GetTolerancesRequest>
{using type = GetTolerancesReply;};
template<> struct ReplyOfT<CheckRequest>
{using type = CheckReply;};
template<> struct ReplyOfT<UpdateBoundsRequest>
{using type = UpdateBoundsReply;};
template<> struct ReplyOfT<UpdateCostsRequest>
{using type = UpdateCostsReply;};
template<> struct ReplyOfT<MatchSizeRequest>
{using type = MatchSizeReply;};
template<> struct ReplyOfT<OnRunRequest>
{using type = OnRunReply;};
template<> struct ReplyOfT<OnCycleUpdateRequest>
{using type = OnCycleUpdateReply;};
template<> struct ReplyOfT<OnActionCompletionRequest>
{using type = OnActionCompletionReply;};
template<> struct ReplyOfT<FindPlanSegmentRequest>
{using type = FindPlanSegmentReply;};
template<class Request>
using ReplyOf = typename ReplyOfT<Request>::type;

}  // namespace nav2_pyif_bridge::protocol
