// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// for_each_field(message, visit) calls visit(name, value) for each field of a structure or body, in
// wire order (optional fields as std::optional, present or not): for code that treats every message
// alike, such as the codec tests' JSON trees.

#pragma once

#include "nav2_pyif_bridge/protocol/bodies.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::protocol
{

template<class Visit>
void for_each_field(const PoseStamped & value, Visit && visit)
{
  visit("frame_id", value.frame_id);
  visit("stamp_ns", value.stamp_ns);
  visit("pose", value.pose);
}

template<class Visit>
void for_each_field(const TwistStamped & value, Visit && visit)
{
  visit("frame_id", value.frame_id);
  visit("stamp_ns", value.stamp_ns);
  visit("twist", value.twist);
}

template<class Visit>
void for_each_field(const Path & value, Visit && visit)
{
  visit("frame_id", value.frame_id);
  visit("stamp_ns", value.stamp_ns);
  visit("poses", value.poses);
}

template<class Visit>
void for_each_field(const Costmap & value, Visit && visit)
{
  visit("version", value.version);
  visit("frame_id", value.frame_id);
  visit("size_x", value.size_x);
  visit("size_y", value.size_y);
  visit("resolution", value.resolution);
  visit("origin_x", value.origin_x);
  visit("origin_y", value.origin_y);
  visit("data", value.data);
  visit("footprint", value.footprint);
  visit("robot_radius", value.robot_radius);
}

template<class Visit>
void for_each_field(const GoalChecker & value, Visit && visit)
{
  visit("xy_goal_tolerance", value.xy_goal_tolerance);
  visit("yaw_goal_tolerance", value.yaw_goal_tolerance);
  visit("trans_stopped_velocity", value.trans_stopped_velocity);
  visit("rot_stopped_velocity", value.rot_stopped_velocity);
  visit("path_length_tolerance", value.path_length_tolerance);
}

template<class Visit>
void for_each_field(const Error & value, Visit && visit)
{
  visit("type", value.type);
  visit("message", value.message);
  visit("traceback", value.traceback);
  visit("python_type", value.python_type);
}

template<class Visit>
void for_each_field(const Input & value, Visit && visit)
{
  visit("name", value.name);
  visit("type", value.type);
  visit("stamp_ns", value.stamp_ns);
  visit("cdr", value.cdr);
}

template<class Visit>
void for_each_field(const DebugOutput & value, Visit && visit)
{
  visit("name", value.name);
  visit("type", value.type);
  visit("cdr", value.cdr);
}

template<class Visit>
void for_each_field(const CarriedCall & value, Visit && visit)
{
  visit("key", value.key);
  visit("payload", value.payload);
}

template<class Visit>
void for_each_field(const ConfigureRequest & value, Visit && visit)
{
  visit("plugin_type", value.plugin_type);
  visit("name", value.name);
  visit("node", value.node);
  visit("params", value.params);
  visit("global_frame", value.global_frame);
  visit("robot_base_frame", value.robot_base_frame);
  visit("costmap", value.costmap);
  visit("nav2_params", value.nav2_params);
}

template<class Visit>
void for_each_field(const ConfigureReply & value, Visit && visit)
{
  visit("declared", value.declared);
  visit("planner", value.planner);
  visit("undeclared", value.undeclared);
  visit("debug_outputs", value.debug_outputs);
}

template<class Visit>
void for_each_field(const ActivateRequest &, Visit &&) {}

template<class Visit>
void for_each_field(const ActivateReply &, Visit &&) {}

template<class Visit>
void for_each_field(const DeactivateRequest &, Visit &&) {}

template<class Visit>
void for_each_field(const DeactivateReply &, Visit &&) {}

template<class Visit>
void for_each_field(const CleanupRequest &, Visit &&) {}

template<class Visit>
void for_each_field(const CleanupReply &, Visit &&) {}

template<class Visit>
void for_each_field(const SetParametersRequest & value, Visit && visit)
{
  visit("params", value.params);
}

template<class Visit>
void for_each_field(const SetParametersReply & value, Visit && visit)
{
  visit("rejected", value.rejected);
}

template<class Visit>
void for_each_field(const SetPlanRequest & value, Visit && visit)
{
  visit("path", value.path);
  visit("goal", value.goal);
}

template<class Visit>
void for_each_field(const SetPlanReply &, Visit &&) {}

template<class Visit>
void for_each_field(const ComputeVelocityCommandsRequest & value, Visit && visit)
{
  visit("pose", value.pose);
  visit("velocity", value.velocity);
  visit("goal_checker", value.goal_checker);
  visit("costmap", value.costmap);
  visit("plan", value.plan);
  visit("goal", value.goal);
  visit("inputs", value.inputs);
  visit("debug_wanted", value.debug_wanted);
  visit("carry", value.carry);
}

template<class Visit>
void for_each_field(const ComputeVelocityCommandsReply & value, Visit && visit)
{
  visit("cmd_vel", value.cmd_vel);
  visit("debug", value.debug);
  visit("carried", value.carried);
}

template<class Visit>
void for_each_field(const SetSpeedLimitRequest & value, Visit && visit)
{
  visit("speed_limit", value.speed_limit);
  visit("percentage", value.percentage);
}

template<class Visit>
void for_each_field(const SetSpeedLimitReply &, Visit &&) {}

template<class Visit>
void for_each_field(const CancelRequest &, Visit &&) {}

template<class Visit>
void for_each_field(const CancelReply & value, Visit && visit)
{
  visit("cancelled", value.cancelled);
}

template<class Visit>
void for_each_field(const ResetRequest &, Visit &&) {}

template<class Visit>
void for_each_field(const ResetReply &, Visit &&) {}

template<class Visit>
void for_each_field(const CreatePlanRequest & value, Visit && visit)
{
  visit("start", value.start);
  visit("goal", value.goal);
  visit("costmap", value.costmap);
  visit("viapoints", value.viapoints);
}

template<class Visit>
void for_each_field(const CreatePlanReply & value, Visit && visit)
{
  visit("path", value.path);
}

template<class Visit>
void for_each_field(const CancelPlanRequest & value, Visit && visit)
{
  visit("target_seq", value.target_seq);
}

template<class Visit>
void for_each_field(const CancelPlanReply & value, Visit && visit)
{
  visit("accepted", value.accepted);
}

template<class Visit>
void for_each_field(const SmoothRequest & value, Visit && visit)
{
  visit("path", value.path);
  visit("max_time", value.max_time);
  visit("costmap", value.costmap);
}

template<class Visit>
void for_each_field(const SmoothReply & value, Visit && visit)
{
  visit("path", value.path);
  visit("was_completed", value.was_completed);
}

template<class Visit>
void for_each_field(const IsGoalReachedRequest & value, Visit && visit)
{
  visit("pose", value.pose);
  visit("goal", value.goal);
  visit("velocity", value.velocity);
  visit("xy_only", value.xy_only);
  visit("carry", value.carry);
}

template<class Visit>
void for_each_field(const IsGoalReachedReply & value, Visit && visit)
{
  visit("reached", value.reached);
  visit("carried", value.carried);
}

template<class Visit>
void for_each_field(const GetTolerancesRequest &, Visit &&) {}

template<class Visit>
void for_each_field(const GetTolerancesReply & value, Visit && visit)
{
  visit("available", value.available);
  visit("pose_tolerance", value.pose_tolerance);
  visit("velocity_tolerance", value.velocity_tolerance);
  visit("path_length_tolerance", value.path_length_tolerance);
}

template<class Visit>
void for_each_field(const CheckRequest & value, Visit && visit)
{
  visit("pose", value.pose);
  visit("carry", value.carry);
}

template<class Visit>
void for_each_field(const CheckReply & value, Visit && visit)
{
  visit("making_progress", value.making_progress);
  visit("carried", value.carried);
}

template<class Visit>
void for_each_field(const UpdateBoundsRequest & value, Visit && visit)
{
  visit("robot_x", value.robot_x);
  visit("robot_y", value.robot_y);
  visit("robot_yaw", value.robot_yaw);
  visit("min_x", value.min_x);
  visit("min_y", value.min_y);
  visit("max_x", value.max_x);
  visit("max_y", value.max_y);
}

template<class Visit>
void for_each_field(const UpdateBoundsReply & value, Visit && visit)
{
  visit("min_x", value.min_x);
  visit("min_y", value.min_y);
  visit("max_x", value.max_x);
  visit("max_y", value.max_y);
}

template<class Visit>
void for_each_field(const UpdateCostsRequest & value, Visit && visit)
{
  visit("min_i", value.min_i);
  visit("min_j", value.min_j);
  visit("max_i", value.max_i);
  visit("max_j", value.max_j);
  visit("origin_x", value.origin_x);
  visit("origin_y", value.origin_y);
  visit("resolution", value.resolution);
}

template<class Visit>
void for_each_field(const UpdateCostsReply & value, Visit && visit)
{
  visit("width", value.width);
  visit("height", value.height);
  visit("costs", value.costs);
  visit("combine", value.combine);
}

template<class Visit>
void for_each_field(const MatchSizeRequest & value, Visit && visit)
{
  visit("size_x", value.size_x);
  visit("size_y", value.size_y);
  visit("resolution", value.resolution);
  visit("origin_x", value.origin_x);
  visit("origin_y", value.origin_y);
}

template<class Visit>
void for_each_field(const MatchSizeReply &, Visit &&) {}

template<class Visit>
void for_each_field(const OnRunRequest & value, Visit && visit)
{
  visit("action", value.action);
  visit("command", value.command);
  visit("pose", value.pose);
  visit("costmap", value.costmap);
}

template<class Visit>
void for_each_field(const OnRunReply & value, Visit && visit)
{
  visit("status", value.status);
  visit("failure", value.failure);
}

template<class Visit>
void for_each_field(const OnCycleUpdateRequest & value, Visit && visit)
{
  visit("pose", value.pose);
  visit("elapsed", value.elapsed);
  visit("costmap", value.costmap);
}

template<class Visit>
void for_each_field(const OnCycleUpdateReply & value, Visit && visit)
{
  visit("status", value.status);
  visit("failure", value.failure);
  visit("cmd_vel", value.cmd_vel);
  visit("feedback", value.feedback);
}

template<class Visit>
void for_each_field(const OnActionCompletionRequest & value, Visit && visit)
{
  visit("status", value.status);
  visit("elapsed", value.elapsed);
}

template<class Visit>
void for_each_field(const OnActionCompletionReply &, Visit &&) {}

template<class Visit>
void for_each_field(const FindPlanSegmentRequest & value, Visit && visit)
{
  visit("pose", value.pose);
}

template<class Visit>
void for_each_field(const FindPlanSegmentReply & value, Visit && visit)
{
  visit("start", value.start);
  visit("end", value.end);
}

}  // namespace nav2_pyif_bridge::protocol
