// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Encode and decode every structure and op body of the schema (the envelopes, envelopes.cpp, call
// these).

#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/protocol/bodies.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"
#include "field_path.hpp"
#include "reader.hpp"
#include "writer.hpp"

namespace nav2_pyif_bridge::protocol::detail
{

// Writes one map, its keys in schema order; throws EncodeError naming the field.
void write(Writer & w, const PoseStamped & value, const FieldPath & where);
void write(Writer & w, const TwistStamped & value, const FieldPath & where);
void write(Writer & w, const Path & value, const FieldPath & where);
void write(Writer & w, const Costmap & value, const FieldPath & where);
void write(Writer & w, const GoalChecker & value, const FieldPath & where);
void write(Writer & w, const Error & value, const FieldPath & where);
void write(Writer & w, const Input & value, const FieldPath & where);
void write(Writer & w, const DebugOutput & value, const FieldPath & where);
void write(Writer & w, const CarriedCall & value, const FieldPath & where);
void write(Writer & w, const ConfigureRequest & value, const FieldPath & where);
void write(Writer & w, const ConfigureReply & value, const FieldPath & where);
void write(Writer & w, const ActivateRequest & value, const FieldPath & where);
void write(Writer & w, const ActivateReply & value, const FieldPath & where);
void write(Writer & w, const DeactivateRequest & value, const FieldPath & where);
void write(Writer & w, const DeactivateReply & value, const FieldPath & where);
void write(Writer & w, const CleanupRequest & value, const FieldPath & where);
void write(Writer & w, const CleanupReply & value, const FieldPath & where);
void write(Writer & w, const SetParametersRequest & value, const FieldPath & where);
void write(Writer & w, const SetParametersReply & value, const FieldPath & where);
void write(Writer & w, const SetPlanRequest & value, const FieldPath & where);
void write(Writer & w, const SetPlanReply & value, const FieldPath & where);
void write(Writer & w, const ComputeVelocityCommandsRequest & value, const FieldPath & where);
void write(Writer & w, const ComputeVelocityCommandsReply & value, const FieldPath & where);
void write(Writer & w, const SetSpeedLimitRequest & value, const FieldPath & where);
void write(Writer & w, const SetSpeedLimitReply & value, const FieldPath & where);
void write(Writer & w, const CancelRequest & value, const FieldPath & where);
void write(Writer & w, const CancelReply & value, const FieldPath & where);
void write(Writer & w, const ResetRequest & value, const FieldPath & where);
void write(Writer & w, const ResetReply & value, const FieldPath & where);
void write(Writer & w, const CreatePlanRequest & value, const FieldPath & where);
void write(Writer & w, const CreatePlanReply & value, const FieldPath & where);
void write(Writer & w, const CancelPlanRequest & value, const FieldPath & where);
void write(Writer & w, const CancelPlanReply & value, const FieldPath & where);
void write(Writer & w, const SmoothRequest & value, const FieldPath & where);
void write(Writer & w, const SmoothReply & value, const FieldPath & where);
void write(Writer & w, const IsGoalReachedRequest & value, const FieldPath & where);
void write(Writer & w, const IsGoalReachedReply & value, const FieldPath & where);
void write(Writer & w, const GetTolerancesRequest & value, const FieldPath & where);
void write(Writer & w, const GetTolerancesReply & value, const FieldPath & where);
void write(Writer & w, const CheckRequest & value, const FieldPath & where);
void write(Writer & w, const CheckReply & value, const FieldPath & where);
void write(Writer & w, const UpdateBoundsRequest & value, const FieldPath & where);
void write(Writer & w, const UpdateBoundsReply & value, const FieldPath & where);
void write(Writer & w, const UpdateCostsRequest & value, const FieldPath & where);
void write(Writer & w, const UpdateCostsReply & value, const FieldPath & where);
void write(Writer & w, const MatchSizeRequest & value, const FieldPath & where);
void write(Writer & w, const MatchSizeReply & value, const FieldPath & where);
void write(Writer & w, const OnRunRequest & value, const FieldPath & where);
void write(Writer & w, const OnRunReply & value, const FieldPath & where);
void write(Writer & w, const OnCycleUpdateRequest & value, const FieldPath & where);
void write(Writer & w, const OnCycleUpdateReply & value, const FieldPath & where);
void write(Writer & w, const OnActionCompletionRequest & value, const FieldPath & where);
void write(Writer & w, const OnActionCompletionReply & value, const FieldPath & where);
void write(Writer & w, const FindPlanSegmentRequest & value, const FieldPath & where);
void write(Writer & w, const FindPlanSegmentReply & value, const FieldPath & where);
void write(Writer & w, const RequestBody & body, const FieldPath & where);
void write(Writer & w, const ReplyBody & body, const FieldPath & where);

// An array field (`many` in the schema): each element written as its kind.
template<class T>
void write(Writer & w, const std::vector<T> & values, const FieldPath & where)
{
  w.array(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    write(w, values[i], where.index(i));
  }
}

// Reads one map, checking every field; throws DecodeError naming the field.
PoseStamped read_pose_stamped(const Object & object, const FieldPath & where);
TwistStamped read_twist_stamped(const Object & object, const FieldPath & where);
Path read_path(const Object & object, const FieldPath & where);
Costmap read_costmap(const Object & object, const FieldPath & where);
GoalChecker read_goal_checker(const Object & object, const FieldPath & where);
Error read_error(const Object & object, const FieldPath & where);
Input read_input(const Object & object, const FieldPath & where);
DebugOutput read_debug_output(const Object & object, const FieldPath & where);
CarriedCall read_carried_call(const Object & object, const FieldPath & where);
ConfigureRequest read_configure_request(const Object & object, const FieldPath & where);
ConfigureReply read_configure_reply(const Object & object, const FieldPath & where);
ActivateRequest read_activate_request(const Object & object, const FieldPath & where);
ActivateReply read_activate_reply(const Object & object, const FieldPath & where);
DeactivateRequest read_deactivate_request(const Object & object, const FieldPath & where);
DeactivateReply read_deactivate_reply(const Object & object, const FieldPath & where);
CleanupRequest read_cleanup_request(const Object & object, const FieldPath & where);
CleanupReply read_cleanup_reply(const Object & object, const FieldPath & where);
SetParametersRequest read_set_parameters_request(const Object & object, const FieldPath & where);
SetParametersReply read_set_parameters_reply(const Object & object, const FieldPath & where);
SetPlanRequest read_set_plan_request(const Object & object, const FieldPath & where);
SetPlanReply read_set_plan_reply(const Object & object, const FieldPath & where);
ComputeVelocityCommandsRequest read_compute_velocity_commands_request(
  const Object & object, const FieldPath & where);
ComputeVelocityCommandsReply read_compute_velocity_commands_reply(
  const Object & object, const FieldPath & where);
SetSpeedLimitRequest read_set_speed_limit_request(const Object & object, const FieldPath & where);
SetSpeedLimitReply read_set_speed_limit_reply(const Object & object, const FieldPath & where);
CancelRequest read_cancel_request(const Object & object, const FieldPath & where);
CancelReply read_cancel_reply(const Object & object, const FieldPath & where);
ResetRequest read_reset_request(const Object & object, const FieldPath & where);
ResetReply read_reset_reply(const Object & object, const FieldPath & where);
CreatePlanRequest read_create_plan_request(const Object & object, const FieldPath & where);
CreatePlanReply read_create_plan_reply(const Object & object, const FieldPath & where);
CancelPlanRequest read_cancel_plan_request(const Object & object, const FieldPath & where);
CancelPlanReply read_cancel_plan_reply(const Object & object, const FieldPath & where);
SmoothRequest read_smooth_request(const Object & object, const FieldPath & where);
SmoothReply read_smooth_reply(const Object & object, const FieldPath & where);
IsGoalReachedRequest read_is_goal_reached_request(const Object & object, const FieldPath & where);
IsGoalReachedReply read_is_goal_reached_reply(const Object & object, const FieldPath & where);
GetTolerancesRequest read_get_tolerances_request(const Object & object, const FieldPath & where);
GetTolerancesReply read_get_tolerances_reply(const Object & object, const FieldPath & where);
CheckRequest read_check_request(const Object & object, const FieldPath & where);
CheckReply read_check_reply(const Object & object, const FieldPath & where);
UpdateBoundsRequest read_update_bounds_request(const Object & object, const FieldPath & where);
UpdateBoundsReply read_update_bounds_reply(const Object & object, const FieldPath & where);
UpdateCostsRequest read_update_costs_request(const Object & object, const FieldPath & where);
UpdateCostsReply read_update_costs_reply(const Object & object, const FieldPath & where);
MatchSizeRequest read_match_size_request(const Object & object, const FieldPath & where);
MatchSizeReply read_match_size_reply(const Object & object, const FieldPath & where);
OnRunRequest read_on_run_request(const Object & object, const FieldPath & where);
OnRunReply read_on_run_reply(const Object & object, const FieldPath & where);
OnCycleUpdateRequest read_on_cycle_update_request(const Object & object, const FieldPath & where);
OnCycleUpdateReply read_on_cycle_update_reply(const Object & object, const FieldPath & where);
OnActionCompletionRequest read_on_action_completion_request(
  const Object & object, const FieldPath & where);
OnActionCompletionReply read_on_action_completion_reply(
  const Object & object, const FieldPath & where);
FindPlanSegmentRequest read_find_plan_segment_request(
  const Object & object, const FieldPath & where);
FindPlanSegmentReply read_find_plan_segment_reply(const Object & object, const FieldPath & where);
RequestBody read_request_body(Op op, const Object & object, const FieldPath & where);
ReplyBody read_reply_body(Op op, const Object & object, const FieldPath & where);

// Bytes of the variable-length fields (text, bin), to reserve before encoding.
std::size_t payload_size(const PoseStamped & value);
std::size_t payload_size(const TwistStamped & value);
std::size_t payload_size(const Path & value);
std::size_t payload_size(const Costmap & value);
std::size_t payload_size(const GoalChecker & value);
std::size_t payload_size(const Error & value);
std::size_t payload_size(const Input & value);
std::size_t payload_size(const DebugOutput & value);
std::size_t payload_size(const CarriedCall & value);
std::size_t payload_size(const ConfigureRequest & value);
std::size_t payload_size(const ConfigureReply & value);
std::size_t payload_size(const ActivateRequest & value);
std::size_t payload_size(const ActivateReply & value);
std::size_t payload_size(const DeactivateRequest & value);
std::size_t payload_size(const DeactivateReply & value);
std::size_t payload_size(const CleanupRequest & value);
std::size_t payload_size(const CleanupReply & value);
std::size_t payload_size(const SetParametersRequest & value);
std::size_t payload_size(const SetParametersReply & value);
std::size_t payload_size(const SetPlanRequest & value);
std::size_t payload_size(const SetPlanReply & value);
std::size_t payload_size(const ComputeVelocityCommandsRequest & value);
std::size_t payload_size(const ComputeVelocityCommandsReply & value);
std::size_t payload_size(const SetSpeedLimitRequest & value);
std::size_t payload_size(const SetSpeedLimitReply & value);
std::size_t payload_size(const CancelRequest & value);
std::size_t payload_size(const CancelReply & value);
std::size_t payload_size(const ResetRequest & value);
std::size_t payload_size(const ResetReply & value);
std::size_t payload_size(const CreatePlanRequest & value);
std::size_t payload_size(const CreatePlanReply & value);
std::size_t payload_size(const CancelPlanRequest & value);
std::size_t payload_size(const CancelPlanReply & value);
std::size_t payload_size(const SmoothRequest & value);
std::size_t payload_size(const SmoothReply & value);
std::size_t payload_size(const IsGoalReachedRequest & value);
std::size_t payload_size(const IsGoalReachedReply & value);
std::size_t payload_size(const GetTolerancesRequest & value);
std::size_t payload_size(const GetTolerancesReply & value);
std::size_t payload_size(const CheckRequest & value);
std::size_t payload_size(const CheckReply & value);
std::size_t payload_size(const UpdateBoundsRequest & value);
std::size_t payload_size(const UpdateBoundsReply & value);
std::size_t payload_size(const UpdateCostsRequest & value);
std::size_t payload_size(const UpdateCostsReply & value);
std::size_t payload_size(const MatchSizeRequest & value);
std::size_t payload_size(const MatchSizeReply & value);
std::size_t payload_size(const OnRunRequest & value);
std::size_t payload_size(const OnRunReply & value);
std::size_t payload_size(const OnCycleUpdateRequest & value);
std::size_t payload_size(const OnCycleUpdateReply & value);
std::size_t payload_size(const OnActionCompletionRequest & value);
std::size_t payload_size(const OnActionCompletionReply & value);
std::size_t payload_size(const FindPlanSegmentRequest & value);
std::size_t payload_size(const FindPlanSegmentReply & value);
std::size_t payload_size(const RequestBody & body);
std::size_t payload_size(const ReplyBody & body);
inline std::size_t payload_size(const std::string & text) {return text.size();}
template<class T>
std::size_t payload_size(const std::vector<T> & values)
{
  std::size_t bytes = 0;
  for (const auto & value : values) {
    bytes += payload_size(value);
  }
  return bytes;
}

}  // namespace nav2_pyif_bridge::protocol::detail
