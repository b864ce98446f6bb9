// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// Encode and decode every structure and op body of the schema, on the hand-written primitives of
// writer.hpp and reader.hpp (PROTOCOL.md section 2's canonical form).

#include "body_codec.hpp"

#include <variant>

namespace nav2_pyif_bridge::protocol::detail
{

// --- encode --------------------------------------------------------------------------------------

void write(Writer & w, const PoseStamped & value, const FieldPath & where)
{
  w.map(3);
  w.key("frame_id");
  w.str(value.frame_id, where.key("frame_id"));
  w.key("stamp_ns");
  w.i64(value.stamp_ns);
  w.key("pose");
  w.floats(value.pose);
}

void write(Writer & w, const TwistStamped & value, const FieldPath & where)
{
  w.map(3);
  w.key("frame_id");
  w.str(value.frame_id, where.key("frame_id"));
  w.key("stamp_ns");
  w.i64(value.stamp_ns);
  w.key("twist");
  w.floats(value.twist);
}

void write(Writer & w, const Path & value, const FieldPath & where)
{
  w.map(3);
  w.key("frame_id");
  w.str(value.frame_id, where.key("frame_id"));
  w.key("stamp_ns");
  w.i64(value.stamp_ns);
  w.key("poses");
  w.rows(value.poses, kPoseRowSize, where.key("poses"));
}

void write(Writer & w, const Costmap & value, const FieldPath & where)
{
  require_cells(value.data.size(), {value.size_x, value.size_y}, where.key("data"));
  w.map(10);
  w.key("version");
  w.u64(value.version);
  w.key("frame_id");
  w.str(value.frame_id, where.key("frame_id"));
  w.key("size_x");
  w.u64(value.size_x);
  w.key("size_y");
  w.u64(value.size_y);
  w.key("resolution");
  w.f64(value.resolution);
  w.key("origin_x");
  w.f64(value.origin_x);
  w.key("origin_y");
  w.f64(value.origin_y);
  w.key("data");
  w.bin(value.data);
  w.key("footprint");
  w.rows(value.footprint, kFootprintRowSize, where.key("footprint"));
  w.key("robot_radius");
  w.f64(value.robot_radius);
}

void write(Writer & w, const GoalChecker & value, const FieldPath &)
{
  w.map(std::size_t{4} + (value.path_length_tolerance ? 1u : 0u));
  w.key("xy_goal_tolerance");
  w.f64(value.xy_goal_tolerance);
  w.key("yaw_goal_tolerance");
  w.f64(value.yaw_goal_tolerance);
  w.key("trans_stopped_velocity");
  w.f64(value.trans_stopped_velocity);
  w.key("rot_stopped_velocity");
  w.f64(value.rot_stopped_velocity);
  if (value.path_length_tolerance) {
    w.key("path_length_tolerance");
    w.f64(*value.path_length_tolerance);
  }
}

void write(Writer & w, const Error & value, const FieldPath & where)
{
  w.map(4);
  w.key("type");
  w.str(value.type, where.key("type"));
  w.key("message");
  w.str(value.message, where.key("message"));
  w.key("traceback");
  w.str(value.traceback, where.key("traceback"));
  w.key("python_type");
  w.str(value.python_type, where.key("python_type"));
}

void write(Writer & w, const Input & value, const FieldPath & where)
{
  w.map(4);
  w.key("name");
  w.str(value.name, where.key("name"));
  w.key("type");
  w.str(value.type, where.key("type"));
  w.key("stamp_ns");
  w.i64(value.stamp_ns);
  w.key("cdr");
  w.bin(value.cdr);
}

void write(Writer & w, const DebugOutput & value, const FieldPath & where)
{
  w.map(3);
  w.key("name");
  w.str(value.name, where.key("name"));
  w.key("type");
  w.str(value.type, where.key("type"));
  w.key("cdr");
  w.bin(value.cdr);
}

void write(Writer & w, const CarriedCall & value, const FieldPath & where)
{
  w.map(2);
  w.key("key");
  w.str(value.key, where.key("key"));
  w.key("payload");
  w.bin(value.payload);
}

void write(Writer & w, const ConfigureRequest & value, const FieldPath & where)
{
  w.map(std::size_t{7} + (value.nav2_params ? 1u : 0u));
  w.key("plugin_type");
  w.str(value.plugin_type, where.key("plugin_type"));
  w.key("name");
  w.str(value.name, where.key("name"));
  w.key("node");
  w.str(value.node, where.key("node"));
  w.key("params");
  write_params(w, value.params, where.key("params"));
  w.key("global_frame");
  w.str(value.global_frame, where.key("global_frame"));
  w.key("robot_base_frame");
  w.str(value.robot_base_frame, where.key("robot_base_frame"));
  w.key("costmap");
  write(w, value.costmap, where.key("costmap"));
  if (value.nav2_params) {
    w.key("nav2_params");
    write_params(w, *value.nav2_params, where.key("nav2_params"));
  }
}

void write(Writer & w, const ConfigureReply & value, const FieldPath & where)
{
  w.map(std::size_t{1} + (value.planner ? 1u : 0u) + (value.undeclared ? 1u : 0u)
      + (value.debug_outputs ? 1u : 0u));
  w.key("declared");
  write_params(w, value.declared, where.key("declared"));
  if (value.planner) {
    w.key("planner");
    w.str(*value.planner, where.key("planner"));
  }
  if (value.undeclared) {
    w.key("undeclared");
    write_str_map(w, *value.undeclared, where.key("undeclared"));
  }
  if (value.debug_outputs) {
    w.key("debug_outputs");
    write_str_map(w, *value.debug_outputs, where.key("debug_outputs"));
  }
}

void write(Writer & w, const ActivateRequest &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const ActivateReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const DeactivateRequest &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const DeactivateReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const CleanupRequest &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const CleanupReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const SetParametersRequest & value, const FieldPath & where)
{
  w.map(1);
  w.key("params");
  write_params(w, value.params, where.key("params"));
}

void write(Writer & w, const SetParametersReply & value, const FieldPath & where)
{
  w.map(1);
  w.key("rejected");
  write_str_map(w, value.rejected, where.key("rejected"));
}

void write(Writer & w, const SetPlanRequest & value, const FieldPath & where)
{
  w.map(std::size_t{1} + (value.goal ? 1u : 0u));
  w.key("path");
  write(w, value.path, where.key("path"));
  if (value.goal) {
    w.key("goal");
    write(w, *value.goal, where.key("goal"));
  }
}

void write(Writer & w, const SetPlanReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const ComputeVelocityCommandsRequest & value, const FieldPath & where)
{
  w.map(std::size_t{2} + (value.goal_checker ? 1u : 0u) + (value.costmap ? 1u : 0u)
      + (value.plan ? 1u : 0u) + (value.goal ? 1u : 0u) + (value.inputs ? 1u : 0u)
      + (value.debug_wanted ? 1u : 0u) + (value.carry ? 1u : 0u));
  w.key("pose");
  write(w, value.pose, where.key("pose"));
  w.key("velocity");
  w.floats(value.velocity);
  if (value.goal_checker) {
    w.key("goal_checker");
    write(w, *value.goal_checker, where.key("goal_checker"));
  }
  if (value.costmap) {
    w.key("costmap");
    write(w, *value.costmap, where.key("costmap"));
  }
  if (value.plan) {
    w.key("plan");
    write(w, *value.plan, where.key("plan"));
  }
  if (value.goal) {
    w.key("goal");
    write(w, *value.goal, where.key("goal"));
  }
  if (value.inputs) {
    w.key("inputs");
    write(w, *value.inputs, where.key("inputs"));
  }
  if (value.debug_wanted) {
    w.key("debug_wanted");
    write(w, *value.debug_wanted, where.key("debug_wanted"));
  }
  if (value.carry) {
    w.key("carry");
    write(w, *value.carry, where.key("carry"));
  }
}

void write(Writer & w, const ComputeVelocityCommandsReply & value, const FieldPath & where)
{
  w.map(std::size_t{1} + (value.debug ? 1u : 0u) + (value.carried ? 1u : 0u));
  w.key("cmd_vel");
  write(w, value.cmd_vel, where.key("cmd_vel"));
  if (value.debug) {
    w.key("debug");
    write(w, *value.debug, where.key("debug"));
  }
  if (value.carried) {
    w.key("carried");
    write(w, *value.carried, where.key("carried"));
  }
}

void write(Writer & w, const SetSpeedLimitRequest & value, const FieldPath &)
{
  w.map(2);
  w.key("speed_limit");
  w.f64(value.speed_limit);
  w.key("percentage");
  w.boolean(value.percentage);
}

void write(Writer & w, const SetSpeedLimitReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const CancelRequest &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const CancelReply & value, const FieldPath &)
{
  w.map(1);
  w.key("cancelled");
  w.boolean(value.cancelled);
}

void write(Writer & w, const ResetRequest &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const ResetReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const CreatePlanRequest & value, const FieldPath & where)
{
  w.map(std::size_t{2} + (value.costmap ? 1u : 0u) + (value.viapoints ? 1u : 0u));
  w.key("start");
  write(w, value.start, where.key("start"));
  w.key("goal");
  write(w, value.goal, where.key("goal"));
  if (value.costmap) {
    w.key("costmap");
    write(w, *value.costmap, where.key("costmap"));
  }
  if (value.viapoints) {
    w.key("viapoints");
    write(w, *value.viapoints, where.key("viapoints"));
  }
}

void write(Writer & w, const CreatePlanReply & value, const FieldPath & where)
{
  w.map(1);
  w.key("path");
  write(w, value.path, where.key("path"));
}

void write(Writer & w, const CancelPlanRequest & value, const FieldPath &)
{
  w.map(1);
  w.key("target_seq");
  w.u64(value.target_seq);
}

void write(Writer & w, const CancelPlanReply & value, const FieldPath &)
{
  w.map(1);
  w.key("accepted");
  w.boolean(value.accepted);
}

void write(Writer & w, const SmoothRequest & value, const FieldPath & where)
{
  w.map(std::size_t{2} + (value.costmap ? 1u : 0u));
  w.key("path");
  write(w, value.path, where.key("path"));
  w.key("max_time");
  w.f64(value.max_time);
  if (value.costmap) {
    w.key("costmap");
    write(w, *value.costmap, where.key("costmap"));
  }
}

void write(Writer & w, const SmoothReply & value, const FieldPath & where)
{
  w.map(2);
  w.key("path");
  write(w, value.path, where.key("path"));
  w.key("was_completed");
  w.boolean(value.was_completed);
}

void write(Writer & w, const IsGoalReachedRequest & value, const FieldPath & where)
{
  w.map(std::size_t{3} + (value.xy_only ? 1u : 0u) + (value.carry ? 1u : 0u));
  w.key("pose");
  w.floats(value.pose);
  w.key("goal");
  w.floats(value.goal);
  w.key("velocity");
  w.floats(value.velocity);
  if (value.xy_only) {
    w.key("xy_only");
    w.boolean(*value.xy_only);
  }
  if (value.carry) {
    w.key("carry");
    write(w, *value.carry, where.key("carry"));
  }
}

void write(Writer & w, const IsGoalReachedReply & value, const FieldPath & where)
{
  w.map(std::size_t{1} + (value.carried ? 1u : 0u));
  w.key("reached");
  w.boolean(value.reached);
  if (value.carried) {
    w.key("carried");
    write(w, *value.carried, where.key("carried"));
  }
}

void write(Writer & w, const GetTolerancesRequest &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const GetTolerancesReply & value, const FieldPath &)
{
  w.map(std::size_t{3} + (value.path_length_tolerance ? 1u : 0u));
  w.key("available");
  w.boolean(value.available);
  w.key("pose_tolerance");
  w.floats(value.pose_tolerance);
  w.key("velocity_tolerance");
  w.floats(value.velocity_tolerance);
  if (value.path_length_tolerance) {
    w.key("path_length_tolerance");
    w.f64(*value.path_length_tolerance);
  }
}

void write(Writer & w, const CheckRequest & value, const FieldPath & where)
{
  w.map(std::size_t{1} + (value.carry ? 1u : 0u));
  w.key("pose");
  write(w, value.pose, where.key("pose"));
  if (value.carry) {
    w.key("carry");
    write(w, *value.carry, where.key("carry"));
  }
}

void write(Writer & w, const CheckReply & value, const FieldPath & where)
{
  w.map(std::size_t{1} + (value.carried ? 1u : 0u));
  w.key("making_progress");
  w.boolean(value.making_progress);
  if (value.carried) {
    w.key("carried");
    write(w, *value.carried, where.key("carried"));
  }
}

void write(Writer & w, const UpdateBoundsRequest & value, const FieldPath &)
{
  w.map(7);
  w.key("robot_x");
  w.f64(value.robot_x);
  w.key("robot_y");
  w.f64(value.robot_y);
  w.key("robot_yaw");
  w.f64(value.robot_yaw);
  w.key("min_x");
  w.f64(value.min_x);
  w.key("min_y");
  w.f64(value.min_y);
  w.key("max_x");
  w.f64(value.max_x);
  w.key("max_y");
  w.f64(value.max_y);
}

void write(Writer & w, const UpdateBoundsReply & value, const FieldPath &)
{
  w.map(4);
  w.key("min_x");
  w.f64(value.min_x);
  w.key("min_y");
  w.f64(value.min_y);
  w.key("max_x");
  w.f64(value.max_x);
  w.key("max_y");
  w.f64(value.max_y);
}

void write(Writer & w, const UpdateCostsRequest & value, const FieldPath &)
{
  w.map(7);
  w.key("min_i");
  w.i64(value.min_i);
  w.key("min_j");
  w.i64(value.min_j);
  w.key("max_i");
  w.i64(value.max_i);
  w.key("max_j");
  w.i64(value.max_j);
  w.key("origin_x");
  w.f64(value.origin_x);
  w.key("origin_y");
  w.f64(value.origin_y);
  w.key("resolution");
  w.f64(value.resolution);
}

void write(Writer & w, const UpdateCostsReply & value, const FieldPath & where)
{
  require_cells(value.costs.size(), {value.width, value.height}, where.key("costs"));
  w.map(4);
  w.key("width");
  w.u64(value.width);
  w.key("height");
  w.u64(value.height);
  w.key("costs");
  w.bin(value.costs);
  w.key("combine");
  w.str(value.combine, where.key("combine"));
}

void write(Writer & w, const MatchSizeRequest & value, const FieldPath &)
{
  w.map(5);
  w.key("size_x");
  w.u64(value.size_x);
  w.key("size_y");
  w.u64(value.size_y);
  w.key("resolution");
  w.f64(value.resolution);
  w.key("origin_x");
  w.f64(value.origin_x);
  w.key("origin_y");
  w.f64(value.origin_y);
}

void write(Writer & w, const MatchSizeReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const OnRunRequest & value, const FieldPath & where)
{
  w.map(std::size_t{3} + (value.costmap ? 1u : 0u));
  w.key("action");
  w.str(value.action, where.key("action"));
  w.key("command");
  write_params(w, value.command, where.key("command"));
  w.key("pose");
  write(w, value.pose, where.key("pose"));
  if (value.costmap) {
    w.key("costmap");
    write(w, *value.costmap, where.key("costmap"));
  }
}

void write(Writer & w, const OnRunReply & value, const FieldPath & where)
{
  w.map(2);
  w.key("status");
  w.str(value.status, where.key("status"));
  w.key("failure");
  w.str(value.failure, where.key("failure"));
}

void write(Writer & w, const OnCycleUpdateRequest & value, const FieldPath & where)
{
  w.map(std::size_t{2} + (value.costmap ? 1u : 0u));
  w.key("pose");
  write(w, value.pose, where.key("pose"));
  w.key("elapsed");
  w.f64(value.elapsed);
  if (value.costmap) {
    w.key("costmap");
    write(w, *value.costmap, where.key("costmap"));
  }
}

void write(Writer & w, const OnCycleUpdateReply & value, const FieldPath & where)
{
  w.map(std::size_t{2} + (value.cmd_vel ? 1u : 0u) + (value.feedback ? 1u : 0u));
  w.key("status");
  w.str(value.status, where.key("status"));
  w.key("failure");
  w.str(value.failure, where.key("failure"));
  if (value.cmd_vel) {
    w.key("cmd_vel");
    write(w, *value.cmd_vel, where.key("cmd_vel"));
  }
  if (value.feedback) {
    w.key("feedback");
    write_params(w, *value.feedback, where.key("feedback"));
  }
}

void write(Writer & w, const OnActionCompletionRequest & value, const FieldPath & where)
{
  w.map(2);
  w.key("status");
  w.str(value.status, where.key("status"));
  w.key("elapsed");
  w.f64(value.elapsed);
}

void write(Writer & w, const OnActionCompletionReply &, const FieldPath &)
{
  w.map(0);
}

void write(Writer & w, const FindPlanSegmentRequest & value, const FieldPath & where)
{
  w.map(1);
  w.key("pose");
  write(w, value.pose, where.key("pose"));
}

void write(Writer & w, const FindPlanSegmentReply & value, const FieldPath &)
{
  w.map(2);
  w.key("start");
  w.u64(value.start);
  w.key("end");
  w.u64(value.end);
}

void write(Writer & w, const RequestBody & body, const FieldPath & where)
{
  std::visit([&](const auto & alternative) {write(w, alternative, where);}, body);
}

void write(Writer & w, const ReplyBody & body, const FieldPath & where)
{
  std::visit([&](const auto & alternative) {write(w, alternative, where);}, body);
}

// --- decode --------------------------------------------------------------------------------------

PoseStamped read_pose_stamped(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  PoseStamped out;
  out.frame_id = m.required("frame_id", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.pose = m.required("pose", read_f64_array<7>);
  return out;
}

TwistStamped read_twist_stamped(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  TwistStamped out;
  out.frame_id = m.required("frame_id", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.twist = m.required("twist", read_f64_array<6>);
  return out;
}

Path read_path(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  Path out;
  out.frame_id = m.required("frame_id", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.poses = m.required("poses", read_rows<kPoseRowSize>);
  return out;
}

Costmap read_costmap(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  Costmap out;
  out.version = m.required("version", read_u64);
  out.frame_id = m.required("frame_id", read_str);
  out.size_x = m.required("size_x", read_u32);
  out.size_y = m.required("size_y", read_u32);
  out.resolution = m.required("resolution", read_f64);
  out.origin_x = m.required("origin_x", read_f64);
  out.origin_y = m.required("origin_y", read_f64);
  out.data = m.required("data", read_bin);
  out.footprint = m.required("footprint", read_rows<kFootprintRowSize>);
  out.robot_radius = m.required("robot_radius", read_f64);
  expect_cells(out.data.size(), {out.size_x, out.size_y}, where.key("data"));
  return out;
}

GoalChecker read_goal_checker(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  GoalChecker out;
  out.xy_goal_tolerance = m.required("xy_goal_tolerance", read_f64);
  out.yaw_goal_tolerance = m.required("yaw_goal_tolerance", read_f64);
  out.trans_stopped_velocity = m.required("trans_stopped_velocity", read_f64);
  out.rot_stopped_velocity = m.required("rot_stopped_velocity", read_f64);
  out.path_length_tolerance = m.optional("path_length_tolerance", read_f64);
  return out;
}

Error read_error(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  Error out;
  out.type = m.required("type", read_str);
  out.message = m.required("message", read_str);
  out.traceback = m.required("traceback", read_str);
  out.python_type = m.required("python_type", read_str);
  return out;
}

Input read_input(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  Input out;
  out.name = m.required("name", read_str);
  out.type = m.required("type", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.cdr = m.required("cdr", read_bin);
  return out;
}

DebugOutput read_debug_output(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  DebugOutput out;
  out.name = m.required("name", read_str);
  out.type = m.required("type", read_str);
  out.cdr = m.required("cdr", read_bin);
  return out;
}

CarriedCall read_carried_call(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CarriedCall out;
  out.key = m.required("key", read_str);
  out.payload = m.required("payload", read_bin);
  return out;
}

ConfigureRequest read_configure_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  ConfigureRequest out;
  out.plugin_type = m.required("plugin_type", read_str);
  out.name = m.required("name", read_str);
  out.node = m.required("node", read_str);
  out.params = m.required("params", read_params);
  out.global_frame = m.required("global_frame", read_str);
  out.robot_base_frame = m.required("robot_base_frame", read_str);
  out.costmap = m.required("costmap", read_costmap);
  out.nav2_params = m.optional("nav2_params", read_params);
  return out;
}

ConfigureReply read_configure_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  ConfigureReply out;
  out.declared = m.required("declared", read_params);
  out.planner = m.optional("planner", read_str);
  out.undeclared = m.optional("undeclared", read_str_map);
  out.debug_outputs = m.optional("debug_outputs", read_str_map);
  return out;
}

ActivateRequest read_activate_request(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return ActivateRequest{};
}

ActivateReply read_activate_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return ActivateReply{};
}

DeactivateRequest read_deactivate_request(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return DeactivateRequest{};
}

DeactivateReply read_deactivate_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return DeactivateReply{};
}

CleanupRequest read_cleanup_request(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return CleanupRequest{};
}

CleanupReply read_cleanup_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return CleanupReply{};
}

SetParametersRequest read_set_parameters_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  SetParametersRequest out;
  out.params = m.required("params", read_params);
  return out;
}

SetParametersReply read_set_parameters_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  SetParametersReply out;
  out.rejected = m.required("rejected", read_str_map);
  return out;
}

SetPlanRequest read_set_plan_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  SetPlanRequest out;
  out.path = m.required("path", read_path);
  out.goal = m.optional("goal", read_pose_stamped);
  return out;
}

SetPlanReply read_set_plan_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return SetPlanReply{};
}

ComputeVelocityCommandsRequest read_compute_velocity_commands_request(
  const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  ComputeVelocityCommandsRequest out;
  out.pose = m.required("pose", read_pose_stamped);
  out.velocity = m.required("velocity", read_f64_array<6>);
  out.goal_checker = m.optional("goal_checker", read_goal_checker);
  out.costmap = m.optional("costmap", read_costmap);
  out.plan = m.optional("plan", read_path);
  out.goal = m.optional("goal", read_pose_stamped);
  out.inputs = m.optional("inputs", read_array<read_input>);
  out.debug_wanted = m.optional("debug_wanted", read_array<read_str>);
  out.carry = m.optional("carry", read_array<read_carried_call>);
  return out;
}

ComputeVelocityCommandsReply read_compute_velocity_commands_reply(
  const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  ComputeVelocityCommandsReply out;
  out.cmd_vel = m.required("cmd_vel", read_twist_stamped);
  out.debug = m.optional("debug", read_array<read_debug_output>);
  out.carried = m.optional("carried", read_array<read_carried_call>);
  return out;
}

SetSpeedLimitRequest read_set_speed_limit_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  SetSpeedLimitRequest out;
  out.speed_limit = m.required("speed_limit", read_f64);
  out.percentage = m.required("percentage", read_bool);
  return out;
}

SetSpeedLimitReply read_set_speed_limit_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return SetSpeedLimitReply{};
}

CancelRequest read_cancel_request(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return CancelRequest{};
}

CancelReply read_cancel_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CancelReply out;
  out.cancelled = m.required("cancelled", read_bool);
  return out;
}

ResetRequest read_reset_request(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return ResetRequest{};
}

ResetReply read_reset_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return ResetReply{};
}

CreatePlanRequest read_create_plan_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CreatePlanRequest out;
  out.start = m.required("start", read_pose_stamped);
  out.goal = m.required("goal", read_pose_stamped);
  out.costmap = m.optional("costmap", read_costmap);
  out.viapoints = m.optional("viapoints", read_path);
  return out;
}

CreatePlanReply read_create_plan_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CreatePlanReply out;
  out.path = m.required("path", read_path);
  return out;
}

CancelPlanRequest read_cancel_plan_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CancelPlanRequest out;
  out.target_seq = m.required("target_seq", read_u64);
  return out;
}

CancelPlanReply read_cancel_plan_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CancelPlanReply out;
  out.accepted = m.required("accepted", read_bool);
  return out;
}

SmoothRequest read_smooth_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  SmoothRequest out;
  out.path = m.required("path", read_path);
  out.max_time = m.required("max_time", read_f64);
  out.costmap = m.optional("costmap", read_costmap);
  return out;
}

SmoothReply read_smooth_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  SmoothReply out;
  out.path = m.required("path", read_path);
  out.was_completed = m.required("was_completed", read_bool);
  return out;
}

IsGoalReachedRequest read_is_goal_reached_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  IsGoalReachedRequest out;
  out.pose = m.required("pose", read_f64_array<7>);
  out.goal = m.required("goal", read_f64_array<7>);
  out.velocity = m.required("velocity", read_f64_array<6>);
  out.xy_only = m.optional("xy_only", read_bool);
  out.carry = m.optional("carry", read_array<read_carried_call>);
  return out;
}

IsGoalReachedReply read_is_goal_reached_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  IsGoalReachedReply out;
  out.reached = m.required("reached", read_bool);
  out.carried = m.optional("carried", read_array<read_carried_call>);
  return out;
}

GetTolerancesRequest read_get_tolerances_request(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return GetTolerancesRequest{};
}

GetTolerancesReply read_get_tolerances_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  GetTolerancesReply out;
  out.available = m.required("available", read_bool);
  out.pose_tolerance = m.required("pose_tolerance", read_f64_array<7>);
  out.velocity_tolerance = m.required("velocity_tolerance", read_f64_array<6>);
  out.path_length_tolerance = m.optional("path_length_tolerance", read_f64);
  return out;
}

CheckRequest read_check_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CheckRequest out;
  out.pose = m.required("pose", read_pose_stamped);
  out.carry = m.optional("carry", read_array<read_carried_call>);
  return out;
}

CheckReply read_check_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  CheckReply out;
  out.making_progress = m.required("making_progress", read_bool);
  out.carried = m.optional("carried", read_array<read_carried_call>);
  return out;
}

UpdateBoundsRequest read_update_bounds_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  UpdateBoundsRequest out;
  out.robot_x = m.required("robot_x", read_f64);
  out.robot_y = m.required("robot_y", read_f64);
  out.robot_yaw = m.required("robot_yaw", read_f64);
  out.min_x = m.required("min_x", read_f64);
  out.min_y = m.required("min_y", read_f64);
  out.max_x = m.required("max_x", read_f64);
  out.max_y = m.required("max_y", read_f64);
  return out;
}

UpdateBoundsReply read_update_bounds_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  UpdateBoundsReply out;
  out.min_x = m.required("min_x", read_f64);
  out.min_y = m.required("min_y", read_f64);
  out.max_x = m.required("max_x", read_f64);
  out.max_y = m.required("max_y", read_f64);
  return out;
}

UpdateCostsRequest read_update_costs_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  UpdateCostsRequest out;
  out.min_i = m.required("min_i", read_i64);
  out.min_j = m.required("min_j", read_i64);
  out.max_i = m.required("max_i", read_i64);
  out.max_j = m.required("max_j", read_i64);
  out.origin_x = m.required("origin_x", read_f64);
  out.origin_y = m.required("origin_y", read_f64);
  out.resolution = m.required("resolution", read_f64);
  return out;
}

UpdateCostsReply read_update_costs_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  UpdateCostsReply out;
  out.width = m.required("width", read_u32);
  out.height = m.required("height", read_u32);
  out.costs = m.required("costs", read_bin);
  out.combine = m.required("combine", read_str);
  expect_cells(out.costs.size(), {out.width, out.height}, where.key("costs"));
  return out;
}

MatchSizeRequest read_match_size_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  MatchSizeRequest out;
  out.size_x = m.required("size_x", read_u32);
  out.size_y = m.required("size_y", read_u32);
  out.resolution = m.required("resolution", read_f64);
  out.origin_x = m.required("origin_x", read_f64);
  out.origin_y = m.required("origin_y", read_f64);
  return out;
}

MatchSizeReply read_match_size_reply(const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return MatchSizeReply{};
}

OnRunRequest read_on_run_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  OnRunRequest out;
  out.action = m.required("action", read_str);
  out.command = m.required("command", read_params);
  out.pose = m.required("pose", read_pose_stamped);
  out.costmap = m.optional("costmap", read_costmap);
  return out;
}

OnRunReply read_on_run_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  OnRunReply out;
  out.status = m.required("status", read_str);
  out.failure = m.required("failure", read_str);
  return out;
}

OnCycleUpdateRequest read_on_cycle_update_request(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  OnCycleUpdateRequest out;
  out.pose = m.required("pose", read_pose_stamped);
  out.elapsed = m.required("elapsed", read_f64);
  out.costmap = m.optional("costmap", read_costmap);
  return out;
}

OnCycleUpdateReply read_on_cycle_update_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  OnCycleUpdateReply out;
  out.status = m.required("status", read_str);
  out.failure = m.required("failure", read_str);
  out.cmd_vel = m.optional("cmd_vel", read_twist_stamped);
  out.feedback = m.optional("feedback", read_params);
  return out;
}

OnActionCompletionRequest read_on_action_completion_request(
  const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  OnActionCompletionRequest out;
  out.status = m.required("status", read_str);
  out.elapsed = m.required("elapsed", read_f64);
  return out;
}

OnActionCompletionReply read_on_action_completion_reply(
  const Object & object, const FieldPath & where)
{
  static_cast<void>(MapReader(object, where));  // a map, even when empty
  return OnActionCompletionReply{};
}

FindPlanSegmentRequest read_find_plan_segment_request(
  const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  FindPlanSegmentRequest out;
  out.pose = m.required("pose", read_pose_stamped);
  return out;
}

FindPlanSegmentReply read_find_plan_segment_reply(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  FindPlanSegmentReply out;
  out.start = m.required("start", read_u64);
  out.end = m.required("end", read_u64);
  return out;
}

RequestBody read_request_body(Op op, const Object & object, const FieldPath & where)
{
  switch (op) {
    case Op::Configure:
      return read_configure_request(object, where);
    case Op::Activate:
      return read_activate_request(object, where);
    case Op::Deactivate:
      return read_deactivate_request(object, where);
    case Op::Cleanup:
      return read_cleanup_request(object, where);
    case Op::SetParameters:
      return read_set_parameters_request(object, where);
    case Op::SetPlan:
      return read_set_plan_request(object, where);
    case Op::ComputeVelocityCommands:
      return read_compute_velocity_commands_request(object, where);
    case Op::SetSpeedLimit:
      return read_set_speed_limit_request(object, where);
    case Op::Cancel:
      return read_cancel_request(object, where);
    case Op::Reset:
      return read_reset_request(object, where);
    case Op::CreatePlan:
      return read_create_plan_request(object, where);
    case Op::CancelPlan:
      return read_cancel_plan_request(object, where);
    case Op::Smooth:
      return read_smooth_request(object, where);
    case Op::IsGoalReached:
      return read_is_goal_reached_request(object, where);
    case Op::GetTolerances:
      return read_get_tolerances_request(object, where);
    case Op::Check:
      return read_check_request(object, where);
    case Op::UpdateBounds:
      return read_update_bounds_request(object, where);
    case Op::UpdateCosts:
      return read_update_costs_request(object, where);
    case Op::MatchSize:
      return read_match_size_request(object, where);
    case Op::OnRun:
      return read_on_run_request(object, where);
    case Op::OnCycleUpdate:
      return read_on_cycle_update_request(object, where);
    case Op::OnActionCompletion:
      return read_on_action_completion_request(object, where);
    case Op::FindPlanSegment:
      return read_find_plan_segment_request(object, where);
  }
  fail(where, "unknown op");  // unreachable: every Op is handled above
}

ReplyBody read_reply_body(Op op, const Object & object, const FieldPath & where)
{
  switch (op) {
    case Op::Configure:
      return read_configure_reply(object, where);
    case Op::Activate:
      return read_activate_reply(object, where);
    case Op::Deactivate:
      return read_deactivate_reply(object, where);
    case Op::Cleanup:
      return read_cleanup_reply(object, where);
    case Op::SetParameters:
      return read_set_parameters_reply(object, where);
    case Op::SetPlan:
      return read_set_plan_reply(object, where);
    case Op::ComputeVelocityCommands:
      return read_compute_velocity_commands_reply(object, where);
    case Op::SetSpeedLimit:
      return read_set_speed_limit_reply(object, where);
    case Op::Cancel:
      return read_cancel_reply(object, where);
    case Op::Reset:
      return read_reset_reply(object, where);
    case Op::CreatePlan:
      return read_create_plan_reply(object, where);
    case Op::CancelPlan:
      return read_cancel_plan_reply(object, where);
    case Op::Smooth:
      return read_smooth_reply(object, where);
    case Op::IsGoalReached:
      return read_is_goal_reached_reply(object, where);
    case Op::GetTolerances:
      return read_get_tolerances_reply(object, where);
    case Op::Check:
      return read_check_reply(object, where);
    case Op::UpdateBounds:
      return read_update_bounds_reply(object, where);
    case Op::UpdateCosts:
      return read_update_costs_reply(object, where);
    case Op::MatchSize:
      return read_match_size_reply(object, where);
    case Op::OnRun:
      return read_on_run_reply(object, where);
    case Op::OnCycleUpdate:
      return read_on_cycle_update_reply(object, where);
    case Op::OnActionCompletion:
      return read_on_action_completion_reply(object, where);
    case Op::FindPlanSegment:
      return read_find_plan_segment_reply(object, where);
  }
  fail(where, "unknown op");  // unreachable: every Op is handled above
}

// --- sizes ---------------------------------------------------------------------------------------

std::size_t payload_size(const PoseStamped & value)
{
  return value.frame_id.size();
}

std::size_t payload_size(const TwistStamped & value)
{
  return value.frame_id.size();
}

std::size_t payload_size(const Path & value)
{
  return value.frame_id.size() + value.poses.size() * 8;
}

std::size_t payload_size(const Costmap & value)
{
  return value.frame_id.size() + value.data.size() + value.footprint.size() * 8;
}

std::size_t payload_size(const GoalChecker &) {return 0;}

std::size_t payload_size(const Error & value)
{
  return value.type.size() + value.message.size() + value.traceback.size()
           + value.python_type.size();
}

std::size_t payload_size(const Input & value)
{
  return value.name.size() + value.type.size() + value.cdr.size();
}

std::size_t payload_size(const DebugOutput & value)
{
  return value.name.size() + value.type.size() + value.cdr.size();
}

std::size_t payload_size(const CarriedCall & value)
{
  return value.key.size() + value.payload.size();
}

std::size_t payload_size(const ConfigureRequest & value)
{
  return value.plugin_type.size() + value.name.size() + value.node.size()
           + value.global_frame.size() + value.robot_base_frame.size()
           + payload_size(value.costmap);
}

std::size_t payload_size(const ConfigureReply & value)
{
  return (value.planner ? (*value.planner).size() : 0);
}

std::size_t payload_size(const ActivateRequest &) {return 0;}

std::size_t payload_size(const ActivateReply &) {return 0;}

std::size_t payload_size(const DeactivateRequest &) {return 0;}

std::size_t payload_size(const DeactivateReply &) {return 0;}

std::size_t payload_size(const CleanupRequest &) {return 0;}

std::size_t payload_size(const CleanupReply &) {return 0;}

std::size_t payload_size(const SetParametersRequest &) {return 0;}

std::size_t payload_size(const SetParametersReply &) {return 0;}

std::size_t payload_size(const SetPlanRequest & value)
{
  return payload_size(value.path) + (value.goal ? payload_size((*value.goal)) : 0);
}

std::size_t payload_size(const SetPlanReply &) {return 0;}

std::size_t payload_size(const ComputeVelocityCommandsRequest & value)
{
  return payload_size(value.pose) + (value.goal_checker ? payload_size((*value.goal_checker)) : 0)
           + (value.costmap ? payload_size((*value.costmap)) : 0)
           + (value.plan ? payload_size((*value.plan)) : 0)
           + (value.goal ? payload_size((*value.goal)) : 0)
           + (value.inputs ? payload_size((*value.inputs)) : 0)
           + (value.debug_wanted ? payload_size((*value.debug_wanted)) : 0)
           + (value.carry ? payload_size((*value.carry)) : 0);
}

std::size_t payload_size(const ComputeVelocityCommandsReply & value)
{
  return payload_size(value.cmd_vel) + (value.debug ? payload_size((*value.debug)) : 0)
           + (value.carried ? payload_size((*value.carried)) : 0);
}

std::size_t payload_size(const SetSpeedLimitRequest &) {return 0;}

std::size_t payload_size(const SetSpeedLimitReply &) {return 0;}

std::size_t payload_size(const CancelRequest &) {return 0;}

std::size_t payload_size(const CancelReply &) {return 0;}

std::size_t payload_size(const ResetRequest &) {return 0;}

std::size_t payload_size(const ResetReply &) {return 0;}

std::size_t payload_size(const CreatePlanRequest & value)
{
  return payload_size(value.start) + payload_size(value.goal)
           + (value.costmap ? payload_size((*value.costmap)) : 0)
           + (value.viapoints ? payload_size((*value.viapoints)) : 0);
}

std::size_t payload_size(const CreatePlanReply & value)
{
  return payload_size(value.path);
}

std::size_t payload_size(const CancelPlanRequest &) {return 0;}

std::size_t payload_size(const CancelPlanReply &) {return 0;}

std::size_t payload_size(const SmoothRequest & value)
{
  return payload_size(value.path) + (value.costmap ? payload_size((*value.costmap)) : 0);
}

std::size_t payload_size(const SmoothReply & value)
{
  return payload_size(value.path);
}

std::size_t payload_size(const IsGoalReachedRequest & value)
{
  return (value.carry ? payload_size((*value.carry)) : 0);
}

std::size_t payload_size(const IsGoalReachedReply & value)
{
  return (value.carried ? payload_size((*value.carried)) : 0);
}

std::size_t payload_size(const GetTolerancesRequest &) {return 0;}

std::size_t payload_size(const GetTolerancesReply &) {return 0;}

std::size_t payload_size(const CheckRequest & value)
{
  return payload_size(value.pose) + (value.carry ? payload_size((*value.carry)) : 0);
}

std::size_t payload_size(const CheckReply & value)
{
  return (value.carried ? payload_size((*value.carried)) : 0);
}

std::size_t payload_size(const UpdateBoundsRequest &) {return 0;}

std::size_t payload_size(const UpdateBoundsReply &) {return 0;}

std::size_t payload_size(const UpdateCostsRequest &) {return 0;}

std::size_t payload_size(const UpdateCostsReply & value)
{
  return value.costs.size() + value.combine.size();
}

std::size_t payload_size(const MatchSizeRequest &) {return 0;}

std::size_t payload_size(const MatchSizeReply &) {return 0;}

std::size_t payload_size(const OnRunRequest & value)
{
  return value.action.size() + payload_size(value.pose)
           + (value.costmap ? payload_size((*value.costmap)) : 0);
}

std::size_t payload_size(const OnRunReply & value)
{
  return value.status.size() + value.failure.size();
}

std::size_t payload_size(const OnCycleUpdateRequest & value)
{
  return payload_size(value.pose) + (value.costmap ? payload_size((*value.costmap)) : 0);
}

std::size_t payload_size(const OnCycleUpdateReply & value)
{
  return value.status.size() + value.failure.size()
           + (value.cmd_vel ? payload_size((*value.cmd_vel)) : 0);
}

std::size_t payload_size(const OnActionCompletionRequest & value)
{
  return value.status.size();
}

std::size_t payload_size(const OnActionCompletionReply &) {return 0;}

std::size_t payload_size(const FindPlanSegmentRequest & value)
{
  return payload_size(value.pose);
}

std::size_t payload_size(const FindPlanSegmentReply &) {return 0;}

std::size_t payload_size(const RequestBody & body)
{
  return std::visit([](const auto & alternative) {return payload_size(alternative);}, body);
}

std::size_t payload_size(const ReplyBody & body)
{
  return std::visit([](const auto & alternative) {return payload_size(alternative);}, body);
}

}  // namespace nav2_pyif_bridge::protocol::detail
