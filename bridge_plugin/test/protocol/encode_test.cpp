// Encoding messages built the way the plugin builds them, and the canonical form's details
// (shortest ints, float64 always, str/bin sizes); encoding refuses what the host could not read.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "test_data.hpp"

namespace nav2_pyif_bridge::protocol::test
{
namespace
{

using Bytes = std::vector<std::uint8_t>;

const char * const kSid = "3f2a9c7e5b1d4e8f9a0b1c2d3e4f5a6b";
const char * const kHost = "host-a-4242-01";

Request request(RequestBody body, std::uint64_t seq, std::uint64_t epoch = 1)
{
  Request out;
  out.sid = kSid;
  out.epoch = epoch;
  out.seq = seq;
  out.body = std::move(body);
  return out;
}

Reply ok_reply(ReplyBody body, std::uint64_t seq, std::int64_t compute_ns)
{
  Reply out;
  out.seq = seq;
  out.outcome = std::move(body);
  out.host = kHost;
  out.compute_ns = compute_ns;
  return out;
}

// x, y and a yaw's quaternion (z, w), as the vectors were generated (values from their JSON).
PoseStamped pose(const char * frame, double x, double y, double qz, double qw)
{
  return PoseStamped{frame, 1700000000123456789, {x, y, 0.0, 0.0, 0.0, qz, qw}};
}

Costmap controller_costmap()
{
  Costmap c;
  c.version = 1;
  c.frame_id = "odom";
  c.size_x = 4;
  c.size_y = 3;
  c.resolution = 0.05;
  c.origin_x = -10.0;
  c.origin_y = -7.5;
  c.data = {0xfd, 0xfe, 0xfe, 0xfe, 0xfd, 0x14, 0x1b, 0x22, 0xfd, 0x21, 0x28, 0xff};
  c.footprint = {0.3, 0.2, 0.3, -0.2, -0.3, -0.2, -0.3, 0.2};
  c.robot_radius = 0.0;
  return c;
}

TEST(EncodeFromScratch, ComputeVelocityCommandsRequest)
{
  ComputeVelocityCommandsRequest body;
  body.pose = pose("odom", 1.0, 2.0, 0.24740395925452294, 0.9689124217106447);
  body.velocity = {0.3, 0.0, 0.0, 0.0, 0.0, 0.1};
  body.goal_checker = GoalChecker{0.25, 0.25, 0.25, 0.25, std::nullopt};
  EXPECT_EQ(encode_request(request(body, 1234)),
    read_vector_bytes("compute_velocity_commands_request"));

  body.goal_checker.reset();
  EXPECT_EQ(encode_request(request(body, std::uint64_t{1} << 32)),
    read_vector_bytes("compute_velocity_commands_no_goal_checker"));
}

// Bytes from the vectors' SCAN_CDR (real CDR of a 3-beam LaserScan; opaque to the codec).
Bytes hex_bytes(const std::string & hex)
{
  Bytes out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

TEST(EncodeFromScratch, InputsAndDebugWanted)
{
  ComputeVelocityCommandsRequest body;
  body.pose = pose("odom", 1.0, 2.0, 0.24740395925452294, 0.9689124217106447);
  body.velocity = {0.3, 0.0, 0.0, 0.0, 0.0, 0.1};
  const Bytes scan = hex_bytes(
    "000100000c00000000000000060000006c617365720000000000c0bf0000c03f0000c03f00000000000000"
    "00cdcccc3d00000041030000000000803f000020400000807f00000000");
  body.inputs = std::vector<Input>{Input{"scan", "sensor_msgs/msg/LaserScan", 12000000000, scan}};
  body.debug_wanted = std::vector<std::string>{"local_plan", "lookahead_point"};
  EXPECT_EQ(encode_request(request(body, 1236)),
    read_vector_bytes("compute_velocity_commands_inputs"));
}

TEST(EncodeFromScratch, ConfigureController)
{
  ConfigureRequest body;
  body.plugin_type = "controller";
  body.name = "FollowPath";
  body.node = "controller_server";
  body.params.set("max_vel_x", 0.5);
  body.params.set("lookahead_dist", 0.6);
  body.params.set("use_rotate", true);
  body.params.set("horizon_steps", std::int64_t{30});
  body.params.set("mode", std::string("fast"));
  body.params.set("weights", std::vector<double>{1.0, 2.5});
  body.params.set("tags", std::vector<std::string>{"a", "b"});
  body.global_frame = "odom";
  body.robot_base_frame = "base_link";
  body.costmap = controller_costmap();
  EXPECT_EQ(encode_request(request(body, 0)), read_vector_bytes("configure_controller"));
}

TEST(EncodeFromScratch, SmallRequests)
{
  EXPECT_EQ(encode_request(request(SetSpeedLimitRequest{50.0, true}, 7)),
    read_vector_bytes("set_speed_limit_percentage"));
  EXPECT_EQ(encode_request(request(CancelPlanRequest{3}, 5)),
    read_vector_bytes("cancel_plan_request"));
  EXPECT_EQ(encode_request(request(ActivateRequest{}, 7)), read_vector_bytes("activate_request"));

  Request future = request(ActivateRequest{}, 1);
  future.v = kProtocolVersion + 1;  // the encoder writes what it is given; only decoders check the version
  EXPECT_EQ(encode_request(future), read_vector_bytes("activate_newer_version"));
}

TEST(EncodeFromScratch, Replies)
{
  TwistStamped cmd{"base_link", 42, {0.4, 0.0, 0.0, 0.0, 0.0, -0.2}};
  EXPECT_EQ(
    encode_reply(ok_reply(ComputeVelocityCommandsReply{cmd, std::nullopt, std::nullopt}, 1234,
    12345)),
    read_vector_bytes("compute_velocity_commands_reply"));
  EXPECT_EQ(encode_reply(ok_reply(CreatePlanReply{Path{"map", 5, {}}}, 7, 12345)),
    read_vector_bytes("create_plan_reply_empty"));
  EXPECT_EQ(encode_reply(ok_reply(SetPlanReply{}, 7, 0)), read_vector_bytes("set_plan_reply"));

  Reply failed;
  failed.seq = 9;
  failed.outcome = Error{"SessionUnknown", "session 3f2a... epoch 2 is not known to this host",
    "", ""};
  failed.host = kHost;
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(encode_reply(failed), read_vector_bytes("error_session_unknown"));
}

// --- canonical details ----------------------------------------------------------------------

// The bytes of `value` as the last field of a message: cancel_plan's target_seq ends a
// request, compute_ns ends a reply.
Bytes tail_of_u64(std::uint64_t value, std::size_t n)
{
  const Bytes all = encode_request(request(CancelPlanRequest{value}, 1));
  return Bytes(all.end() - static_cast<std::ptrdiff_t>(n), all.end());
}

Bytes tail_of_i64(std::int64_t value, std::size_t n)
{
  const Bytes all = encode_reply(ok_reply(ActivateReply{}, 1, value));
  return Bytes(all.end() - static_cast<std::ptrdiff_t>(n), all.end());
}

TEST(Canonical, IntsTakeTheirShortestForm)
{
  EXPECT_EQ(tail_of_u64(0, 1), (Bytes{0x00}));
  EXPECT_EQ(tail_of_u64(127, 1), (Bytes{0x7f}));
  EXPECT_EQ(tail_of_u64(128, 2), (Bytes{0xcc, 0x80}));
  EXPECT_EQ(tail_of_u64(255, 2), (Bytes{0xcc, 0xff}));
  EXPECT_EQ(tail_of_u64(256, 3), (Bytes{0xcd, 0x01, 0x00}));
  EXPECT_EQ(tail_of_u64(65536, 5), (Bytes{0xce, 0x00, 0x01, 0x00, 0x00}));
  EXPECT_EQ(tail_of_u64(0xFFFFFFFFu, 5), (Bytes{0xce, 0xff, 0xff, 0xff, 0xff}));
  EXPECT_EQ(tail_of_u64(std::uint64_t{1} << 32, 9),
    (Bytes{0xcf, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00}));
  // Signed fields: non-negative values use the unsigned forms, as msgpack-python does.
  EXPECT_EQ(tail_of_i64(200, 2), (Bytes{0xcc, 0xc8}));
  EXPECT_EQ(tail_of_i64(-1, 1), (Bytes{0xff}));
  EXPECT_EQ(tail_of_i64(-32, 1), (Bytes{0xe0}));
  EXPECT_EQ(tail_of_i64(-33, 2), (Bytes{0xd0, 0xdf}));
  EXPECT_EQ(tail_of_i64(-129, 3), (Bytes{0xd1, 0xff, 0x7f}));
  EXPECT_EQ(tail_of_i64(-32769, 5), (Bytes{0xd2, 0xff, 0xff, 0x7f, 0xff}));
  EXPECT_EQ(tail_of_i64(INT64_MIN, 9),
    (Bytes{0xd3, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}));
}

TEST(Canonical, FloatsAreAlwaysFloat64)
{
  const Bytes all = encode_request(request(SetSpeedLimitRequest{1.0, false}, 1));
  // ... "speed_limit" 0xcb <8 bytes of 1.0> "percentage" false
  const Bytes one{0xcb, 0x3f, 0xf0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};
  const Bytes tail(all.end() - 9 - 12, all.end() - 12);
  EXPECT_EQ(tail, one);
}

TEST(Canonical, StrAndBinHeadersBySize)
{
  const auto host_header = [](std::size_t size) {
      Reply reply = ok_reply(ActivateReply{}, 1, 0);
      reply.host = std::string(size, 'h');
      const Bytes all = encode_reply(reply);
      // ... <host str> 0xaa "compute_ns" 0x00: the header sits before the text and 12 bytes.
      const std::size_t header = size < 32 ? 1 : size < 256 ? 2 : size < 65536 ? 3 : 5;
      const auto end = all.end() - static_cast<std::ptrdiff_t>(12 + size);
      return Bytes(end - static_cast<std::ptrdiff_t>(header), end);
    };
  EXPECT_EQ(host_header(31), (Bytes{0xbf}));
  EXPECT_EQ(host_header(32), (Bytes{0xd9, 0x20}));
  EXPECT_EQ(host_header(256), (Bytes{0xda, 0x01, 0x00}));
  EXPECT_EQ(host_header(65536), (Bytes{0xdb, 0x00, 0x01, 0x00, 0x00}));

  const auto poses_header = [](std::size_t poses) {
      const Path path{"map", 0, std::vector<double>(poses * kPoseRowSize, 1.0)};
      const Bytes all = encode_request(request(SetPlanRequest{path, std::nullopt}, 1));
      const std::size_t header = poses * 56 < 256 ? 2 : poses * 56 < 65536 ? 3 : 5;
      const auto end = all.end() - static_cast<std::ptrdiff_t>(poses * 56);
      return Bytes(end - static_cast<std::ptrdiff_t>(header), end);
    };
  EXPECT_EQ(poses_header(0), (Bytes{0xc4, 0x00}));
  EXPECT_EQ(poses_header(4), (Bytes{0xc4, 0xe0}));
  EXPECT_EQ(poses_header(5), (Bytes{0xc5, 0x01, 0x18}));
  EXPECT_EQ(poses_header(1170), (Bytes{0xc5, 0xff, 0xf0}));  // 65520 bytes
  EXPECT_EQ(poses_header(1171), (Bytes{0xc6, 0x00, 0x01, 0x00, 0x28}));
}

TEST(Canonical, PackedPosesAreLittleEndianRows)
{
  const Path path{"map", 0, {1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0}};
  const Bytes all = encode_request(request(SetPlanRequest{path, std::nullopt}, 1));
  const Bytes x(all.end() - 56, all.end() - 48);
  EXPECT_EQ(x, (Bytes{0, 0, 0, 0, 0, 0, 0xf0, 0x3f}));  // 1.0, little-endian
  const Request back = decode_request(all);
  EXPECT_EQ(std::get<SetPlanRequest>(back.body).path.poses, path.poses);
}

// --- refusals -------------------------------------------------------------------------------

std::string encode_outcome(const Request & r)
{
  try {
    encode_request(r);
    return "encoded";
  } catch (const EncodeError & e) {
    return e.what();
  }
}

TEST(EncodeErrors, PackedArraysMustHoldWholeRows)
{
  EXPECT_EQ(
    encode_outcome(
      request(SetPlanRequest{Path{"map", 0, std::vector<double>(8)}, std::nullopt}, 1)),
    "set_plan request body.path.poses: 8 values is not a whole number of rows of 7");

  ConfigureRequest configure;
  configure.costmap = controller_costmap();
  configure.costmap.footprint.pop_back();
  EXPECT_EQ(encode_outcome(request(configure, 1)),
    "configure request body.costmap.footprint: 7 values is not a whole number of rows of 2");
}

TEST(EncodeErrors, CostmapDataMustMatchItsSize)
{
  CreatePlanRequest plan;
  plan.costmap = controller_costmap();
  plan.costmap->size_x = 5;
  EXPECT_EQ(encode_outcome(request(plan, 1)),
    "create_plan request body.costmap.data: 12 bytes, but size 5 x 3 needs 15");
}

TEST(EncodeErrors, TextMustBeUtf8)
{
  ComputeVelocityCommandsRequest body;
  body.pose.frame_id = "odom\xff";
  EXPECT_EQ(encode_outcome(request(body, 1)),
    "compute_velocity_commands request body.pose.frame_id: "
    "not valid UTF-8 (msgpack str is UTF-8 text)");

  SetParametersRequest params;
  params.params.set("names", std::vector<std::string>{"ok", "\xc0\xaf"});  // overlong '/'
  EXPECT_EQ(encode_outcome(request(params, 1)),
    "set_parameters request body.params['names'][1]: "
    "not valid UTF-8 (msgpack str is UTF-8 text)");
}

}  // namespace
}  // namespace nav2_pyif_bridge::protocol::test
