// Parameter maps: every ParamValue alternative survives the wire, and maps keep their order.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "json_tree.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"

namespace nav2_pyif_bridge::protocol::test
{
namespace
{

Reply configure_reply(Params declared)
{
  Reply reply;
  reply.seq = 3;
  reply.host = "h";
  ConfigureReply body;
  body.declared = std::move(declared);
  reply.outcome = ReplyBody{std::move(body)};
  return reply;
}

Params round_trip(const Params & params)
{
  const Reply decoded = decode_reply(encode_reply(configure_reply(params)), Op::Configure);
  return std::get<ConfigureReply>(decoded.body()).declared;
}

TEST(OrderedMap, KeepsInsertionOrderAndReplacesInPlace)
{
  StringMap map;
  map.set("b", "1");
  map.set("a", "2");
  map.set("b", "3");  // replaced where it was, as in a Python dict
  ASSERT_EQ(map.size(), 2u);
  EXPECT_EQ(map.begin()->first, "b");
  EXPECT_EQ(map.begin()->second, "3");
  ASSERT_NE(map.find("a"), nullptr);
  EXPECT_EQ(*map.find("a"), "2");
  EXPECT_EQ(map.find("c"), nullptr);
}

TEST(Params, EveryAlternativeSurvivesTheWire)
{
  Params params;
  params.set("flag", true);
  params.set("steps", std::int64_t{-30});
  params.set("big", std::numeric_limits<std::int64_t>::max());
  params.set("small", std::numeric_limits<std::int64_t>::min());
  params.set("gain", 0.5);
  params.set("whole", 2.0);  // stays a float: 2.0, not 2
  params.set("mode", std::string("fast"));
  params.set("flags", std::vector<bool>{true, false});
  params.set("ids", std::vector<std::int64_t>{1, -2, 300});
  params.set("weights", std::vector<double>{1.0, 2.5});
  params.set("tags", std::vector<std::string>{"a", "ü"});

  const Params back = round_trip(params);
  ASSERT_EQ(back.size(), params.size());
  auto expected = params.begin();
  for (const auto & [name, value] : back) {
    EXPECT_EQ(name, expected->first);
    EXPECT_EQ(value, expected->second) << name;
    ++expected;
  }
}

TEST(Params, AnEmptyArrayDecodesAsAnEmptyFloatArray)
{
  Params params;
  params.set("none", std::vector<std::string>{});
  const Params back = round_trip(params);
  ASSERT_NE(back.find("none"), nullptr);
  EXPECT_EQ(*back.find("none"), ParamValue{std::vector<double>{}});
  // Either way the bytes are the same: an empty array has no element type.
  EXPECT_EQ(encode_reply(configure_reply(back)), encode_reply(configure_reply(params)));
}

TEST(Params, IntsBeyondInt64AreRefused)
{
  Json reply = read_vector_json("configure_reply");
  reply["body"]["declared"]["k_rep"] = std::numeric_limits<std::uint64_t>::max();
  try {
    decode_reply(pack_json(reply), Op::Configure);
    FAIL() << "a uint64 parameter was accepted";
  } catch (const DecodeError & e) {
    EXPECT_STREQ(e.what(),
      "configure reply body.declared['k_rep']: "
      "int 18446744073709551615 is out of the int64 range");
  }
}

TEST(Params, DeclaredParamsOfTheVectorHaveTheirTypes)
{
  const Reply reply = decode_reply(read_vector_bytes("configure_reply"), Op::Configure);
  const Params & declared = std::get<ConfigureReply>(reply.body()).declared;
  ASSERT_NE(declared.find("max_vel_x"), nullptr);
  EXPECT_EQ(*declared.find("max_vel_x"), ParamValue{0.5});
  ASSERT_NE(declared.find("k_rep"), nullptr);
  EXPECT_EQ(*declared.find("k_rep"), ParamValue{std::int64_t{2}});
}

}  // namespace
}  // namespace nav2_pyif_bridge::protocol::test
