// The shared vectors are the contract (PROTOCOL.md section 11): for every vector in
// index.json, decoding gives the expected tree and re-encoding gives the same bytes.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "json_tree.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "test_data.hpp"

namespace nav2_pyif_bridge::protocol::test
{
namespace
{

// Read when the tests are registered. An unreadable index becomes one entry that fails with
// the reason, rather than zero tests that pass.
std::vector<VectorEntry> index_entries()
{
  try {
    return load_index();
  } catch (const std::exception & e) {
    return {{"index_json_unreadable", "", "", e.what()}};
  }
}

Op op_named(const std::string & name)
{
  const auto op = op_from_name(name);
  if (!op) {
    throw std::runtime_error("index.json names an unknown op: " + name);
  }
  return *op;
}

class Vector : public ::testing::TestWithParam<VectorEntry> {};

TEST_P(Vector, DecodesToItsTreeAndReencodesByteForByte)
{
  const VectorEntry & entry = GetParam();
  ASSERT_FALSE(entry.kind.empty()) << entry.description;
  const std::vector<std::uint8_t> bytes = read_vector_bytes(entry.name);
  const Json expected = read_vector_json(entry.name);
  const Op op = op_named(entry.op);

  if (expected.at("v") != kProtocolVersion) {
    // A message of another protocol version must be refused, not half-read.
    try {
      if (entry.kind == "request") {
        decode_request(bytes);
      } else {
        decode_reply(bytes, op);
      }
      FAIL() << entry.name << ": a version " << expected.at("v") << " message was accepted";
    } catch (const DecodeError & e) {
      EXPECT_EQ(e.error_type(), error_type::kVersionMismatch) << e.what();
    }
    return;
  }

  if (entry.kind == "request") {
    const Request request = decode_request(bytes);
    EXPECT_EQ(request.op(), op);
    EXPECT_EQ(first_difference(expected, to_json(request)), "");
    EXPECT_TRUE(encode_request(request) == bytes) << "re-encoding " << entry.name
                                                  << " gave different bytes";
  } else {
    ASSERT_EQ(entry.kind, "reply");
    const Reply reply = decode_reply(bytes, op);
    if (reply.ok()) {
      EXPECT_EQ(op_of(reply.body()), op);
    }
    EXPECT_EQ(first_difference(expected, to_json(reply)), "");
    EXPECT_TRUE(encode_reply(reply) == bytes) << "re-encoding " << entry.name
                                              << " gave different bytes";
  }
}

INSTANTIATE_TEST_SUITE_P(
  SharedVectors, Vector, ::testing::ValuesIn(index_entries()),
  [](const ::testing::TestParamInfo<VectorEntry> & param) {return param.param.name;});

TEST(VectorIndex, CoversEveryOpInBothDirections)
{
  std::set<std::string> requests;
  std::set<std::string> replies;
  for (const VectorEntry & entry : load_index()) {
    (entry.kind == "request" ? requests : replies).insert(entry.op);
  }
  const std::set<std::string> all(kOpNames.begin(), kOpNames.end());
  EXPECT_EQ(requests, all);
  EXPECT_EQ(replies, all);
}

TEST(VectorIndex, ANewerVersionIsRefusedWithVersionMismatch)
{
  const auto bytes = read_vector_bytes("activate_newer_version");
  try {
    decode_request(bytes);
    FAIL() << "a newer version's request was accepted";
  } catch (const DecodeError & e) {
    EXPECT_EQ(e.error_type(), error_type::kVersionMismatch);
    EXPECT_EQ(e.field_path(), "request.v");
    EXPECT_STREQ(e.what(), "request.v: request speaks protocol version 3; this codec speaks 2");
  }
}

TEST(VectorIndex, LargeVectorsDecodeToTheirFullSize)
{
  const Request big = decode_request(read_vector_bytes("create_plan_costmap_1000"));
  const auto & body = std::get<CreatePlanRequest>(big.body);
  ASSERT_TRUE(body.costmap.has_value());
  EXPECT_EQ(body.costmap->data.size(), 1000u * 1000u);
  const Request plan = decode_request(read_vector_bytes("set_plan_1000"));
  EXPECT_EQ(std::get<SetPlanRequest>(plan.body).path.pose_count(), 1000u);
}

}  // namespace
}  // namespace nav2_pyif_bridge::protocol::test
