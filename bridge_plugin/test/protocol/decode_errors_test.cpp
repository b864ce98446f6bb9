// Decoding what breaks the tables: every failure is a DecodeError with the protocol error
// type a host answers with and the path of the field at fault; nothing else escapes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "json_tree.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "test_data.hpp"

namespace nav2_pyif_bridge::protocol::test
{
namespace
{

using Bytes = std::vector<std::uint8_t>;

// "<error type>: <message>" of decoding the bytes, or "accepted".
std::string request_outcome(const Bytes & bytes)
{
  try {
    decode_request(bytes);
    return "accepted";
  } catch (const DecodeError & e) {
    return e.error_type() + ": " + e.what();
  }
}

std::string request_outcome(const Json & tree) {return request_outcome(pack_json(tree));}

std::string reply_outcome(const Json & tree, Op op)
{
  try {
    decode_reply(pack_json(tree), op);
    return "accepted";
  } catch (const DecodeError & e) {
    return e.error_type() + ": " + e.what();
  }
}

// The small vectors, as trees to break.
Json cvc() {return read_vector_json("compute_velocity_commands_request");}
Json configure() {return read_vector_json("configure_controller");}

TEST(DecodeErrors, MissingFieldNamesTheMapAndTheField)
{
  Json tree = cvc();
  tree["body"]["pose"].erase("frame_id");
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.pose: missing field 'frame_id'");

  tree = cvc();
  tree.erase("sid");
  EXPECT_EQ(request_outcome(tree), "BadRequest: request: missing field 'sid'");

  tree = configure();
  tree["body"]["costmap"].erase("robot_radius");
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.costmap: missing field 'robot_radius'");
}

TEST(DecodeErrors, WrongTypeNamesTheFieldAndBothTypes)
{
  Json tree = cvc();
  tree["body"]["pose"]["frame_id"] = 5;
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.pose.frame_id: expected str, got int");

  tree = cvc();
  tree["body"]["velocity"][2] = "fast";
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.velocity[2]: expected float, got str");

  tree = cvc();
  tree["body"]["goal_checker"] = Json::array();
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.goal_checker: expected map, got array");

  tree = cvc();
  tree["epoch"] = true;  // bool is not an int on the wire
  EXPECT_EQ(request_outcome(tree), "BadRequest: request.epoch: expected int, got bool");

  tree = configure();
  tree["body"]["costmap"]["data"] = "not bytes";
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.costmap.data: expected bin, got str");

  tree = configure();
  tree["body"]["costmap"]["resolution"] = Json{{"$bin", "00"}};
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.costmap.resolution: expected float, got bin");
}

TEST(DecodeErrors, FloatArraysNeedTheirExactLength)
{
  Json tree = cvc();
  tree["body"]["velocity"].erase(5);
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.velocity: "
    "expected an array of 6 floats, got 5");
  tree = cvc();
  tree["body"]["pose"]["pose"] = 1.0;
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.pose.pose: "
    "expected an array of 7 floats, got float");
}

TEST(DecodeErrors, IntegerRangesAreChecked)
{
  Json tree = cvc();
  tree["seq"] = -1;
  EXPECT_EQ(request_outcome(tree), "BadRequest: request.seq: expected an int >= 0, got -1");

  tree = cvc();
  tree["epoch"] = 0;
  EXPECT_EQ(request_outcome(tree), "BadRequest: request.epoch: expected an int >= 1, got 0");

  tree = configure();
  tree["body"]["costmap"]["size_x"] = std::uint64_t{1} << 32;
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.costmap.size_x: "
    "int 4294967296 is out of the uint32 range");

  tree = cvc();
  tree["body"]["pose"]["stamp_ns"] = std::uint64_t{1} << 63;
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body.pose.stamp_ns: "
    "int 9223372036854775808 is out of the int64 range");

  tree = cvc();
  tree["body"]["pose"]["stamp_ns"] = -5;  // stamps are signed
  EXPECT_EQ(request_outcome(tree), "accepted");
}

TEST(DecodeErrors, PackedArraysMustHoldWholeRows)
{
  Json tree = read_vector_json("set_plan_request");
  tree["body"]["path"]["poses"] = Json{{"$bin", std::string(57 * 2, '0')}};
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: set_plan request body.path.poses: "
    "57 bytes is not a whole number of rows of 7 float64 (56 bytes)");

  tree = configure();
  tree["body"]["costmap"]["footprint"] = Json{{"$bin", std::string(24 * 2, '0')}};
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.costmap.footprint: "
    "24 bytes is not a whole number of rows of 2 float64 (16 bytes)");
}

TEST(DecodeErrors, CostmapDataMustMatchItsSize)
{
  Json tree = configure();  // 4 x 3
  tree["body"]["costmap"]["size_y"] = 4;
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.costmap.data: 12 bytes, but size 4 x 4 needs 16");
}

TEST(DecodeErrors, StringsMustBeUtf8)
{
  Json tree = cvc();
  tree["sid"] = std::string("\xC3\x28");  // an invalid 2-byte sequence
  EXPECT_EQ(request_outcome(tree), "BadRequest: request.sid: str is not valid UTF-8");
  tree["sid"] = std::string("\xED\xA0\x80");  // a UTF-16 surrogate, refused by Python too
  EXPECT_EQ(request_outcome(tree), "BadRequest: request.sid: str is not valid UTF-8");
  tree["sid"] = std::string("\xF0\x9F\xA4\x96");  // U+1F916, four bytes, fine
  EXPECT_EQ(request_outcome(tree), "accepted");
}

TEST(DecodeErrors, UnknownOpListsTheKnownOnes)
{
  Json tree = cvc();
  tree["op"] = "fly";
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: request.op: unknown op 'fly'; known: configure, activate, deactivate, "
    "cleanup, set_parameters, set_plan, compute_velocity_commands, set_speed_limit, cancel, "
    "reset, create_plan, cancel_plan, smooth, is_goal_reached, get_tolerances, check, "
    "update_bounds, update_costs, match_size, on_run, on_cycle_update, on_action_completion, "
    "find_plan_segment");
}

TEST(DecodeErrors, VersionIsCheckedFirst)
{
  Json tree = cvc();
  tree["v"] = 3;
  tree.erase("sid");  // a newer version's message may differ in anything else
  EXPECT_EQ(request_outcome(tree),
    "VersionMismatch: request.v: request speaks protocol version 3; this codec speaks 2");

  tree = cvc();
  tree.erase("v");
  EXPECT_EQ(request_outcome(tree),
    "VersionMismatch: request.v: request speaks protocol version missing; "
    "this codec speaks 2");

  tree = cvc();
  tree["v"] = "1";
  EXPECT_EQ(request_outcome(tree),
    "VersionMismatch: request.v: request speaks protocol version of type str; "
    "this codec speaks 2");

  Json reply = read_vector_json("cancel_reply");
  reply["v"] = 0;
  EXPECT_EQ(reply_outcome(reply, Op::Cancel),
    "VersionMismatch: reply.v: reply speaks protocol version 0; this codec speaks 2");
}

TEST(DecodeErrors, NotAMapAtTheTop)
{
  EXPECT_EQ(request_outcome(Json::array({1, 2})),
    "BadRequest: request: expected map, got array");
  EXPECT_EQ(request_outcome(Bytes{}),
    "BadRequest: request: not valid msgpack: insufficient bytes");
}

TEST(DecodeErrors, EveryTruncationIsRefused)
{
  struct Case
  {
    const char * name;
    bool is_request;
    Op op;
  };
  for (const Case & c : {Case{"compute_velocity_commands_request", true, Op::ComputeVelocityCommands},
      Case{"configure_controller", true, Op::Configure},
      Case{"error_python_exception", false, Op::ComputeVelocityCommands},
      Case{"create_plan_reply", false, Op::CreatePlan}})
  {
    const Bytes bytes = read_vector_bytes(c.name);
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      const Bytes cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(size));
      try {
        if (c.is_request) {
          decode_request(cut);
        } else {
          decode_reply(cut, c.op);
        }
        ADD_FAILURE() << c.name << " cut to " << size << " bytes was accepted";
      } catch (const DecodeError & e) {
        ASSERT_EQ(e.error_type(), "BadRequest") << c.name << " cut to " << size << ": "
                                                << e.what();
      }
    }
  }
  // The 1 MB costmap, cut inside its data.
  const Bytes big = read_vector_bytes("create_plan_costmap_1000");
  const Bytes cut(big.begin(), big.begin() + static_cast<std::ptrdiff_t>(big.size() / 2));
  EXPECT_EQ(request_outcome(cut), "BadRequest: request: not valid msgpack: insufficient bytes");
}

TEST(DecodeErrors, TrailingBytesAreRefused)
{
  Bytes bytes = read_vector_bytes("activate_request");
  bytes.push_back(0xC0);
  EXPECT_EQ(request_outcome(bytes),
    "BadRequest: request: not valid msgpack: 1 extra bytes after the message");
}

TEST(DecodeErrors, ForgedLengthsFailWithoutAllocatingThem)
{
  // An array, a map, a str and a bin each claiming 2^32 - 1 elements / bytes.
  for (const int header : {0xDD, 0xDF, 0xDB, 0xC6}) {
    const Bytes forged{static_cast<std::uint8_t>(header), 0xFF, 0xFF, 0xFF, 0xFF, 0x00};
    const std::string outcome = request_outcome(forged);
    EXPECT_EQ(outcome.rfind("BadRequest: request: not valid msgpack: ", 0), 0u) << outcome;
  }
  // Nesting far deeper than any message, hidden under a key decoders would ignore.
  Json tree = read_vector_json("activate_request");
  Json deep = Json::array();
  for (int i = 0; i < 200; ++i) {
    deep = Json::array({deep});
  }
  tree["x_future"] = deep;
  const std::string outcome = request_outcome(tree);
  EXPECT_EQ(outcome.rfind("BadRequest: request: not valid msgpack: ", 0), 0u) << outcome;
}

TEST(DecodeErrors, CorruptedBytesFailOnlyWithDecodeError)
{
  // Every byte of a few vectors replaced by a few values: the decoder may accept the result
  // (a changed value is still a message) but must never crash or throw anything else.
  struct Case
  {
    const char * name;
    bool is_request;
    Op op;
  };
  for (const Case & c : {Case{"compute_velocity_commands_request", true, Op::ComputeVelocityCommands},
      Case{"configure_controller", true, Op::Configure},
      Case{"set_plan_request", true, Op::SetPlan},
      Case{"set_parameters_reply", false, Op::SetParameters},
      Case{"error_no_path_unicode", false, Op::CreatePlan}})
  {
    const Bytes original = read_vector_bytes(c.name);
    for (std::size_t i = 0; i < original.size(); ++i) {
      for (const int value : {0x00, 0x7F, 0x80, 0xC1, 0xFF, original[i] ^ 0x01}) {
        Bytes bytes = original;
        bytes[i] = static_cast<std::uint8_t>(value);
        try {
          if (c.is_request) {
            decode_request(bytes);
          } else {
            decode_reply(bytes, c.op);
          }
        } catch (const DecodeError &) {
        } catch (const std::exception & e) {
          ADD_FAILURE() << c.name << " byte " << i << " = " << value << ": " << e.what();
        }
      }
    }
  }
}

TEST(DecodeErrors, ParamsAreScalarsOrArraysOfOneScalarType)
{
  Json tree = configure();
  tree["body"]["params"]["nested"] = Json{{"a", 1}};
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.params['nested']: "
    "parameter 'nested': map is not bool/int/float/str or an array of one of those");

  tree = configure();
  tree["body"]["params"]["mixed"] = Json::array({1, 2.5});
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.params['mixed']: "
    "parameter 'mixed': array mixes float and int");

  tree = configure();
  tree["body"]["params"]["grid"] = Json::array({Json::array({1})});
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.params['grid'][0]: "
    "parameter 'grid': array is not bool/int/float/str or an array of one of those");

  tree = configure();
  tree["body"]["params"]["unset"] = nullptr;
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: configure request body.params['unset']: "
    "parameter 'unset': nil is not bool/int/float/str or an array of one of those");

  Json reply = read_vector_json("set_parameters_reply");
  reply["body"]["rejected"]["max_vel_x"] = 3;
  EXPECT_EQ(reply_outcome(reply, Op::SetParameters),
    "BadRequest: set_parameters reply body.rejected['max_vel_x']: expected str, got int");
}

TEST(DecodeErrors, ParamNamesMustBeStrings)
{
  // JSON has only string keys, so this one map is written by hand:
  // request {v: 2, op: set_parameters, sid: s, epoch: 1, seq: 1, body: {params: {1: true}}}
  Bytes bytes = pack_json(Json{{"v", kProtocolVersion}, {"op", "set_parameters"}, {"sid", "s"},
      {"epoch", 1}, {"seq", 1}});
  bytes[0] = 0x86;  // six entries: append the body
  const Bytes body{0xA4, 'b', 'o', 'd', 'y', 0x81, 0xA6, 'p', 'a', 'r', 'a', 'm', 's', 0x81,
    0x01, 0xC3};
  bytes.insert(bytes.end(), body.begin(), body.end());
  EXPECT_EQ(request_outcome(bytes),
    "BadRequest: set_parameters request body.params: a parameter name is int, not str");
}

TEST(DecodeErrors, ReplyErrorsNameTheReply)
{
  Json reply = read_vector_json("error_session_unknown");
  reply["ok"] = false;
  reply.erase("error");
  EXPECT_EQ(reply_outcome(reply, Op::SetPlan),
    "BadRequest: reply: an error reply (ok false) without its 'error' map");

  reply = read_vector_json("error_session_unknown");
  reply["error"].erase("traceback");
  EXPECT_EQ(reply_outcome(reply, Op::SetPlan),
    "BadRequest: reply.error: missing field 'traceback'");

  // A reply read as the answer to another op: its body does not fit.
  reply = read_vector_json("compute_velocity_commands_reply");
  EXPECT_EQ(reply_outcome(reply, Op::Cancel),
    "BadRequest: cancel reply body: missing field 'cancelled'");

  reply = read_vector_json("cancel_reply");
  reply["compute_ns"] = 1.5;
  EXPECT_EQ(reply_outcome(reply, Op::Cancel),
    "BadRequest: reply.compute_ns: expected int, got float");
}

// --- what decoders accept ---------------------------------------------------------------

TEST(DecodeLeniency, IntWhereFloatIsSpecified)
{
  Json tree = read_vector_json("set_speed_limit_percentage");
  tree["body"]["speed_limit"] = 50;  // an int on the wire
  const Bytes bytes = pack_json(tree);
  ASSERT_NE(bytes, read_vector_bytes("set_speed_limit_percentage"));
  const Request request = decode_request(bytes);
  EXPECT_EQ(std::get<SetSpeedLimitRequest>(request.body).speed_limit, 50.0);
  // Re-encoding gives the canonical form: a float64.
  EXPECT_EQ(encode_request(request), read_vector_bytes("set_speed_limit_percentage"));

  tree = cvc();
  tree["body"]["velocity"] = Json::array({0, -1, 0, 0, 0, 2});
  const auto velocity =
    std::get<ComputeVelocityCommandsRequest>(decode_request(pack_json(tree)).body).velocity;
  EXPECT_EQ(velocity[1], -1.0);
  EXPECT_EQ(velocity[5], 2.0);
}

TEST(DecodeLeniency, Float32IsAFloat)
{
  Json tree = read_vector_json("set_speed_limit_percentage");
  tree["body"]["speed_limit"] = Json{{"$float32", 50.0}};
  const Request request = decode_request(pack_json(tree));
  EXPECT_EQ(encode_request(request), read_vector_bytes("set_speed_limit_percentage"));
}

TEST(DecodeLeniency, UnknownKeysAreIgnoredAtEveryLevel)
{
  Json tree = configure();
  tree["x_top"] = Json::array({1, "two", Json{{"three", nullptr}}});
  tree["body"]["x_body"] = Json{{"$bin", "0102"}};
  tree["body"]["costmap"]["x_costmap"] = -7;
  const Request request = decode_request(pack_json(tree));
  EXPECT_EQ(encode_request(request), read_vector_bytes("configure_controller"));

  Json reply = read_vector_json("compute_velocity_commands_reply");
  reply["body"]["cmd_vel"]["x_covariance"] = Json::array({0.0});
  reply["x_host_load"] = 0.5;
  EXPECT_EQ(encode_reply(decode_reply(pack_json(reply), Op::ComputeVelocityCommands)),
    read_vector_bytes("compute_velocity_commands_reply"));
}

TEST(DecodeLeniency, NilCountsAsAbsent)
{
  Json tree = cvc();
  tree["body"]["goal_checker"] = nullptr;  // optional: absent
  const auto body = std::get<ComputeVelocityCommandsRequest>(decode_request(pack_json(tree)).body);
  EXPECT_FALSE(body.goal_checker.has_value());

  tree = cvc();
  tree["body"]["velocity"] = nullptr;  // required: missing
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body: missing field 'velocity'");
}

TEST(DecodeLeniency, AbsentBodyIsAnEmptyMap)
{
  // As in the Python codec: fine for ops with an empty body, a missing field otherwise.
  Json tree = read_vector_json("activate_request");
  tree.erase("body");
  EXPECT_EQ(encode_request(decode_request(pack_json(tree))), read_vector_bytes("activate_request"));
  tree = cvc();
  tree.erase("body");
  EXPECT_EQ(request_outcome(tree),
    "BadRequest: compute_velocity_commands request body: missing field 'pose'");
}

TEST(DecodeLeniency, RepeatedKeyCountsWithItsLastValue)
{
  // {v: 1, ..., seq: 1, seq: 2}: a Python dict keeps the last value; so does this codec.
  Json tree = read_vector_json("activate_request");
  tree.erase("body");
  Bytes bytes = pack_json(tree);
  bytes[0] = static_cast<std::uint8_t>(bytes[0] + 1);
  const Bytes again{0xA3, 's', 'e', 'q', 0x02};
  bytes.insert(bytes.end(), again.begin(), again.end());
  EXPECT_EQ(decode_request(bytes).seq, 2u);
}

TEST(DecodeLeniency, NonFiniteFloatsSurvive)
{
  // Section 7 says where they are errors; the codec carries them unchanged.
  const Request request = decode_request(read_vector_bytes("compute_velocity_commands_nan_velocity"));
  const auto & velocity = std::get<ComputeVelocityCommandsRequest>(request.body).velocity;
  EXPECT_TRUE(std::isnan(velocity[0]));
  EXPECT_TRUE(std::isinf(velocity[2]) && velocity[2] > 0);
  EXPECT_TRUE(std::isinf(velocity[3]) && velocity[3] < 0);
  EXPECT_TRUE(velocity[4] == 0.0 && std::signbit(velocity[4]));
}

}  // namespace
}  // namespace nav2_pyif_bridge::protocol::test
