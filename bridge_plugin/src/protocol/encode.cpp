// Messages -> canonical bytes. Each function writes one table of PROTOCOL.md section 13, its
// keys in the table's order; optional fields are left out when absent (never nil).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "field_path.hpp"
#include "writer.hpp"

namespace nav2_pyif_bridge::protocol
{
namespace
{

using detail::FieldPath;
using detail::Writer;

template<class... Fs>
struct Overloaded : Fs ...
{
  using Fs::operator()...;
};
template<class... Fs>
Overloaded(Fs...)->Overloaded<Fs...>;

// Room for the envelope and a typical body; large arrays are added on top of it.
constexpr std::size_t kSmallMessage = 512;

template<std::size_t N>
void write_floats(Writer & w, const std::array<double, N> & values)
{
  w.array(N);
  for (const double value : values) {
    w.f64(value);
  }
}

void write_packed(Writer & w, const std::vector<double> & values, std::size_t row_size,
  const FieldPath & where)
{
  if (values.size() % row_size != 0) {
    throw EncodeError(where.str() + ": " + std::to_string(values.size()) +
            " values is not a whole number of rows of " + std::to_string(row_size));
  }
  w.packed_f64(values);
}

void write(Writer & w, const PoseStamped & pose, const FieldPath & where)
{
  w.map(3);
  w.key("frame_id");
  w.str(pose.frame_id, where.key("frame_id"));
  w.key("stamp_ns");
  w.i64(pose.stamp_ns);
  w.key("pose");
  write_floats(w, pose.pose);
}

void write(Writer & w, const TwistStamped & twist, const FieldPath & where)
{
  w.map(3);
  w.key("frame_id");
  w.str(twist.frame_id, where.key("frame_id"));
  w.key("stamp_ns");
  w.i64(twist.stamp_ns);
  w.key("twist");
  write_floats(w, twist.twist);
}

void write(Writer & w, const Path & path, const FieldPath & where)
{
  w.map(3);
  w.key("frame_id");
  w.str(path.frame_id, where.key("frame_id"));
  w.key("stamp_ns");
  w.i64(path.stamp_ns);
  w.key("poses");
  write_packed(w, path.poses, kPoseRowSize, where.key("poses"));
}

void write(Writer & w, const Costmap & costmap, const FieldPath & where)
{
  const std::uint64_t cells = std::uint64_t{costmap.size_x} * costmap.size_y;
  if (costmap.data.size() != cells) {
    throw EncodeError(where.key("data").str() + ": " + std::to_string(costmap.data.size()) +
            " bytes, but size " + std::to_string(costmap.size_x) + " x " +
            std::to_string(costmap.size_y) + " needs " + std::to_string(cells));
  }
  w.map(10);
  w.key("version");
  w.u64(costmap.version);
  w.key("frame_id");
  w.str(costmap.frame_id, where.key("frame_id"));
  w.key("size_x");
  w.u64(costmap.size_x);
  w.key("size_y");
  w.u64(costmap.size_y);
  w.key("resolution");
  w.f64(costmap.resolution);
  w.key("origin_x");
  w.f64(costmap.origin_x);
  w.key("origin_y");
  w.f64(costmap.origin_y);
  w.key("data");
  w.bin(costmap.data.data(), costmap.data.size());
  w.key("footprint");
  write_packed(w, costmap.footprint, kFootprintRowSize, where.key("footprint"));
  w.key("robot_radius");
  w.f64(costmap.robot_radius);
}

void write(Writer & w, const GoalChecker & checker)
{
  w.map(4);
  w.key("xy_goal_tolerance");
  w.f64(checker.xy_goal_tolerance);
  w.key("yaw_goal_tolerance");
  w.f64(checker.yaw_goal_tolerance);
  w.key("trans_stopped_velocity");
  w.f64(checker.trans_stopped_velocity);
  w.key("rot_stopped_velocity");
  w.f64(checker.rot_stopped_velocity);
}

void write(Writer & w, const Error & error, const FieldPath & where)
{
  w.map(4);
  w.key("type");
  w.str(error.type, where.key("type"));
  w.key("message");
  w.str(error.message, where.key("message"));
  w.key("traceback");
  w.str(error.traceback, where.key("traceback"));
  w.key("python_type");
  w.str(error.python_type, where.key("python_type"));
}

void write_param(Writer & w, const ParamValue & value, const FieldPath & where)
{
  std::visit(
    Overloaded{
      [&](bool v) {w.boolean(v);},
      [&](std::int64_t v) {w.i64(v);},
      [&](double v) {w.f64(v);},
      [&](const std::string & v) {w.str(v, where);},
      [&](const std::vector<bool> & v) {
        w.array(v.size());
        for (const bool item : v) {
          w.boolean(item);
        }
      },
      [&](const std::vector<std::int64_t> & v) {
        w.array(v.size());
        for (const std::int64_t item : v) {
          w.i64(item);
        }
      },
      [&](const std::vector<double> & v) {
        w.array(v.size());
        for (const double item : v) {
          w.f64(item);
        }
      },
      [&](const std::vector<std::string> & v) {
        w.array(v.size());
        for (std::size_t i = 0; i < v.size(); ++i) {
          w.str(v[i], where.index(i));
        }
      },
    },
    value);
}

void write(Writer & w, const Params & params, const FieldPath & where)
{
  w.map(params.size());
  for (const auto & [name, value] : params) {
    w.str(name, where);
    write_param(w, value, where.param(name));
  }
}

void write(Writer & w, const StringMap & map, const FieldPath & where)
{
  w.map(map.size());
  for (const auto & [name, value] : map) {
    w.str(name, where);
    w.str(value, where.param(name));
  }
}

// Bytes to reserve for the large arrays a body carries.
std::size_t payload_size(const Costmap & costmap)
{
  return costmap.data.size() + costmap.footprint.size() * 8;
}

std::size_t payload_size(const std::optional<Costmap> & costmap)
{
  return costmap ? payload_size(*costmap) : 0;
}

// --- request bodies -------------------------------------------------------------------------

void write_body(Writer & w, const ConfigureRequest & body, const FieldPath & where)
{
  w.map(7);
  w.key("plugin_type");
  w.str(body.plugin_type, where.key("plugin_type"));
  w.key("name");
  w.str(body.name, where.key("name"));
  w.key("node");
  w.str(body.node, where.key("node"));
  w.key("params");
  write(w, body.params, where.key("params"));
  w.key("global_frame");
  w.str(body.global_frame, where.key("global_frame"));
  w.key("robot_base_frame");
  w.str(body.robot_base_frame, where.key("robot_base_frame"));
  w.key("costmap");
  write(w, body.costmap, where.key("costmap"));
}

void write_body(Writer & w, const SetParametersRequest & body, const FieldPath & where)
{
  w.map(1);
  w.key("params");
  write(w, body.params, where.key("params"));
}

void write_body(Writer & w, const SetPlanRequest & body, const FieldPath & where)
{
  w.map(1);
  w.key("path");
  write(w, body.path, where.key("path"));
}

void write_body(Writer & w, const ComputeVelocityCommandsRequest & body, const FieldPath & where)
{
  w.map(std::size_t{2} + (body.goal_checker ? 1u : 0u) + (body.costmap ? 1u : 0u));
  w.key("pose");
  write(w, body.pose, where.key("pose"));
  w.key("velocity");
  write_floats(w, body.velocity);
  if (body.goal_checker) {
    w.key("goal_checker");
    write(w, *body.goal_checker);
  }
  if (body.costmap) {
    w.key("costmap");
    write(w, *body.costmap, where.key("costmap"));
  }
}

void write_body(Writer & w, const SetSpeedLimitRequest & body, const FieldPath &)
{
  w.map(2);
  w.key("speed_limit");
  w.f64(body.speed_limit);
  w.key("percentage");
  w.boolean(body.percentage);
}

void write_body(Writer & w, const CreatePlanRequest & body, const FieldPath & where)
{
  w.map(std::size_t{2} + (body.costmap ? 1u : 0u));
  w.key("start");
  write(w, body.start, where.key("start"));
  w.key("goal");
  write(w, body.goal, where.key("goal"));
  if (body.costmap) {
    w.key("costmap");
    write(w, *body.costmap, where.key("costmap"));
  }
}

void write_body(Writer & w, const CancelPlanRequest & body, const FieldPath &)
{
  w.map(1);
  w.key("target_seq");
  w.u64(body.target_seq);
}

// --- reply bodies ---------------------------------------------------------------------------

void write_body(Writer & w, const ConfigureReply & body, const FieldPath & where)
{
  w.map(1);
  w.key("declared");
  write(w, body.declared, where.key("declared"));
}

void write_body(Writer & w, const SetParametersReply & body, const FieldPath & where)
{
  w.map(1);
  w.key("rejected");
  write(w, body.rejected, where.key("rejected"));
}

void write_body(Writer & w, const ComputeVelocityCommandsReply & body, const FieldPath & where)
{
  w.map(1);
  w.key("cmd_vel");
  write(w, body.cmd_vel, where.key("cmd_vel"));
}

void write_body(Writer & w, const CancelReply & body, const FieldPath &)
{
  w.map(1);
  w.key("cancelled");
  w.boolean(body.cancelled);
}

void write_body(Writer & w, const CreatePlanReply & body, const FieldPath & where)
{
  w.map(1);
  w.key("path");
  write(w, body.path, where.key("path"));
}

void write_body(Writer & w, const CancelPlanReply & body, const FieldPath &)
{
  w.map(1);
  w.key("accepted");
  w.boolean(body.accepted);
}

// The bodies that are empty maps on the wire: activate, deactivate, cleanup, reset, ...
template<class Body>
auto write_body(Writer & w, const Body &, const FieldPath &)
->std::enable_if_t<std::is_empty_v<Body>>
{
  w.map(0);
}

std::size_t request_capacity(const RequestBody & body)
{
  return kSmallMessage + std::visit(
    Overloaded{
      [](const ConfigureRequest & b) {return payload_size(b.costmap);},
      [](const SetPlanRequest & b) {return b.path.poses.size() * 8;},
      [](const ComputeVelocityCommandsRequest & b) {return payload_size(b.costmap);},
      [](const CreatePlanRequest & b) {return payload_size(b.costmap);},
      [](const auto &) {return std::size_t{0};},
    },
    body);
}

}  // namespace

Bytes encode_request(const Request & request)
{
  const std::string_view op = op_name(request.op());
  const FieldPath root("request");
  Writer w(request_capacity(request.body));
  w.map(6);
  w.key("v");
  w.i64(request.v);
  w.key("op");
  w.key(op);
  w.key("sid");
  w.str(request.sid, root.key("sid"));
  w.key("epoch");
  w.u64(request.epoch);
  w.key("seq");
  w.u64(request.seq);
  w.key("body");
  const FieldPath body_path(op, " request body");
  std::visit([&](const auto & body) {write_body(w, body, body_path);}, request.body);
  return w.take();
}

Bytes encode_reply(const Reply & reply)
{
  const FieldPath root("reply");
  std::size_t capacity = kSmallMessage;
  if (reply.ok()) {
    if (const auto * plan = std::get_if<CreatePlanReply>(&reply.body())) {
      capacity += plan->path.poses.size() * 8;
    }
  } else {
    capacity += reply.error().message.size() + reply.error().traceback.size();
  }
  Writer w(capacity);
  w.map(6);
  w.key("v");
  w.i64(reply.v);
  w.key("seq");
  w.u64(reply.seq);
  w.key("ok");
  w.boolean(reply.ok());
  if (reply.ok()) {
    w.key("body");
    const FieldPath body_path(op_name(op_of(reply.body())), " reply body");
    std::visit([&](const auto & body) {write_body(w, body, body_path);}, reply.body());
  } else {
    w.key("error");
    write(w, reply.error(), root.key("error"));
  }
  w.key("host");
  w.str(reply.host, root.key("host"));
  w.key("compute_ns");
  w.i64(reply.compute_ns);
  return w.take();
}

}  // namespace nav2_pyif_bridge::protocol
