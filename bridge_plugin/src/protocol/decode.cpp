// Bytes -> messages. Each function reads one table of PROTOCOL.md section 13 and checks every
// field's type; the envelope is checked before the body, as the Python codec does, so both
// codecs refuse the same messages with the same error types.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <utility>

#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "field_path.hpp"
#include "reader.hpp"

namespace nav2_pyif_bridge::protocol
{
namespace
{

using detail::FieldPath;
using detail::MapReader;
using detail::Object;
using detail::read_bool;
using detail::read_f64;
using detail::read_i64;
using detail::read_params;
using detail::read_str;
using detail::read_u32;
using detail::read_u64;

// --- parsing --------------------------------------------------------------------------------

// str and bin objects point into the caller's buffer instead of being copied into the zone:
// the buffer outlives the tree (both live only during one decode call), and the fields are
// copied once, into the message, anyway.
bool reference_input(msgpack::type::object_type, std::size_t, void *)
{
  return true;
}

msgpack::object_handle parse(const std::uint8_t * data, std::size_t size, const char * what)
{
  // Every element takes at least one byte (a map entry two), so no valid message has more
  // elements than bytes; these limits keep a forged length such as "array of 2^32 - 1" from
  // allocating gigabytes before the parser notices the data is short.
  const std::size_t elements = size;
  const msgpack::unpack_limit limit(elements, elements / 2, size, size, size, 64);
  std::size_t offset = 0;
  msgpack::object_handle handle;
  try {
    handle = msgpack::unpack(
      reinterpret_cast<const char *>(data), size, offset, reference_input, nullptr, limit);
  } catch (const std::exception & e) {
    // insufficient_bytes, parse_error, *_size_overflow, depth_size_overflow, ...
    throw DecodeError(error_type::kBadRequest, what, std::string("not valid msgpack: ") + e.what());
  }
  if (offset != size) {
    throw DecodeError(
            error_type::kBadRequest, what,
            "not valid msgpack: " + std::to_string(size - offset) + " extra bytes after the message");
  }
  return handle;
}

// `v` comes first: a message of another version may differ in anything else, so nothing
// else is read before it is known to be ours.
void check_version(const MapReader & message, const char * what)
{
  const Object * v = message.find("v");
  if (v != nullptr && v->type == msgpack::type::POSITIVE_INTEGER &&
    v->via.u64 == static_cast<std::uint64_t>(kProtocolVersion))
  {
    return;
  }
  std::string theirs = "missing";
  if (v != nullptr) {
    theirs = v->type == msgpack::type::POSITIVE_INTEGER ? std::to_string(v->via.u64) :
      v->type == msgpack::type::NEGATIVE_INTEGER ? std::to_string(v->via.i64) :
      std::string("of type ") + detail::type_name(*v);
  }
  throw DecodeError(
          error_type::kVersionMismatch, std::string(what) + ".v",
          std::string(what) + " speaks protocol version " + theirs + "; this codec speaks " +
          std::to_string(kProtocolVersion));
}

// The body map, or an empty one when absent: the Python codec reads a missing body as {}.
const Object & body_of(const MapReader & message)
{
  static const Object empty_map = [] {
      Object o;
      o.type = msgpack::type::MAP;
      o.via.map.size = 0;
      o.via.map.ptr = nullptr;
      return o;
    }();
  const Object * body = message.find("body");
  return body != nullptr ? *body : empty_map;
}

// --- structures -----------------------------------------------------------------------------

PoseStamped read_pose(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  PoseStamped out;
  out.frame_id = m.required("frame_id", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.pose = m.required("pose", detail::read_f64_array<7>);
  return out;
}

TwistStamped read_twist(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  TwistStamped out;
  out.frame_id = m.required("frame_id", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.twist = m.required("twist", detail::read_f64_array<6>);
  return out;
}

std::vector<double> read_poses(const Object & object, const FieldPath & where)
{
  return detail::read_packed_f64(object, where, kPoseRowSize);
}

std::vector<double> read_footprint(const Object & object, const FieldPath & where)
{
  return detail::read_packed_f64(object, where, kFootprintRowSize);
}

Path read_path(const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  Path out;
  out.frame_id = m.required("frame_id", read_str);
  out.stamp_ns = m.required("stamp_ns", read_i64);
  out.poses = m.required("poses", read_poses);
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
  out.data = m.required("data", detail::read_bin);
  out.footprint = m.required("footprint", read_footprint);
  out.robot_radius = m.required("robot_radius", read_f64);
  // The Python codec leaves this to the host's Costmap view; checking it here means a
  // decoded Costmap can always be indexed as my * size_x + mx.
  const std::uint64_t cells = std::uint64_t{out.size_x} * out.size_y;
  if (out.data.size() != cells) {
    detail::fail(where.key("data"), std::to_string(out.data.size()) + " bytes, but size " +
      std::to_string(out.size_x) + " x " + std::to_string(out.size_y) + " needs " +
      std::to_string(cells));
  }
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

// --- request bodies -------------------------------------------------------------------------

RequestBody read_request_body(Op op, const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  switch (op) {
    case Op::Configure: {
        ConfigureRequest body;
        body.plugin_type = m.required("plugin_type", read_str);
        body.name = m.required("name", read_str);
        body.node = m.required("node", read_str);
        body.params = m.required("params", read_params);
        body.global_frame = m.required("global_frame", read_str);
        body.robot_base_frame = m.required("robot_base_frame", read_str);
        body.costmap = m.required("costmap", read_costmap);
        return body;
      }
    case Op::Activate:
      return ActivateRequest{};
    case Op::Deactivate:
      return DeactivateRequest{};
    case Op::Cleanup:
      return CleanupRequest{};
    case Op::SetParameters:
      return SetParametersRequest{m.required("params", read_params)};
    case Op::SetPlan:
      return SetPlanRequest{m.required("path", read_path)};
    case Op::ComputeVelocityCommands: {
        ComputeVelocityCommandsRequest body;
        body.pose = m.required("pose", read_pose);
        body.velocity = m.required("velocity", detail::read_f64_array<6>);
        body.goal_checker = m.optional("goal_checker", read_goal_checker);
        body.costmap = m.optional("costmap", read_costmap);
        return body;
      }
    case Op::SetSpeedLimit: {
        SetSpeedLimitRequest body;
        body.speed_limit = m.required("speed_limit", read_f64);
        body.percentage = m.required("percentage", read_bool);
        return body;
      }
    case Op::Cancel:
      return CancelRequest{};
    case Op::Reset:
      return ResetRequest{};
    case Op::CreatePlan: {
        CreatePlanRequest body;
        body.start = m.required("start", read_pose);
        body.goal = m.required("goal", read_pose);
        body.costmap = m.optional("costmap", read_costmap);
        return body;
      }
    case Op::CancelPlan:
      return CancelPlanRequest{m.required("target_seq", read_u64)};
  }
  detail::fail(where, "unknown op");  // unreachable: every Op is handled above
}

// --- reply bodies ---------------------------------------------------------------------------

ReplyBody read_reply_body(Op op, const Object & object, const FieldPath & where)
{
  const MapReader m(object, where);
  switch (op) {
    case Op::Configure:
      return ConfigureReply{m.required("declared", read_params)};
    case Op::Activate:
      return ActivateReply{};
    case Op::Deactivate:
      return DeactivateReply{};
    case Op::Cleanup:
      return CleanupReply{};
    case Op::SetParameters:
      return SetParametersReply{m.required("rejected", detail::read_str_map)};
    case Op::SetPlan:
      return SetPlanReply{};
    case Op::ComputeVelocityCommands:
      return ComputeVelocityCommandsReply{m.required("cmd_vel", read_twist)};
    case Op::SetSpeedLimit:
      return SetSpeedLimitReply{};
    case Op::Cancel:
      return CancelReply{m.required("cancelled", read_bool)};
    case Op::Reset:
      return ResetReply{};
    case Op::CreatePlan:
      return CreatePlanReply{m.required("path", read_path)};
    case Op::CancelPlan:
      return CancelPlanReply{m.required("accepted", read_bool)};
  }
  detail::fail(where, "unknown op");  // unreachable: every Op is handled above
}

std::string known_ops()
{
  std::string out;
  for (const auto name : kOpNames) {
    out.append(out.empty() ? "" : ", ").append(name);
  }
  return out;
}

}  // namespace

// --- envelopes ------------------------------------------------------------------------------

Request decode_request(const std::uint8_t * data, std::size_t size)
{
  const msgpack::object_handle handle = parse(data, size, "request");
  const FieldPath root("request");
  const MapReader m(handle.get(), root);
  check_version(m, "request");

  Request out;
  const std::string op_text = m.required("op", read_str);
  const auto op = op_from_name(op_text);
  if (!op) {
    detail::fail(root.key("op"), "unknown op '" + op_text + "'; known: " + known_ops());
  }
  out.sid = m.required("sid", read_str);
  out.epoch = m.required("epoch", read_u64);
  if (out.epoch < 1) {
    detail::fail(root.key("epoch"), "expected an int >= 1, got 0");
  }
  out.seq = m.required("seq", read_u64);
  out.body = read_request_body(*op, body_of(m), FieldPath(op_name(*op), " request body"));
  return out;
}

Reply decode_reply(const std::uint8_t * data, std::size_t size, Op op)
{
  const msgpack::object_handle handle = parse(data, size, "reply");
  const FieldPath root("reply");
  const MapReader m(handle.get(), root);
  check_version(m, "reply");

  Reply out;
  out.seq = m.required("seq", read_u64);
  const bool ok = m.required("ok", read_bool);
  out.host = m.required("host", read_str);
  out.compute_ns = m.required("compute_ns", read_i64);
  if (ok) {
    out.outcome = read_reply_body(op, body_of(m), FieldPath(op_name(op), " reply body"));
  } else {
    const Object * error = m.find("error");
    if (error == nullptr) {
      detail::fail(root, "an error reply (ok false) without its 'error' map");
    }
    out.outcome = read_error(*error, root.key("error"));
  }
  return out;
}

}  // namespace nav2_pyif_bridge::protocol
