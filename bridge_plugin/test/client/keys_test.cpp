// The key rules of the shared vector protocol/vectors/keys.json, which the Python KeySpace
// (nav2_pyif_protocol.keys) wrote: every op's key, the cancel, host and token keys, and each
// prefix refused with the same message or accepted.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <stdexcept>
#include <string>

#include "nav2_pyif_bridge/client/keys.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;
using Json = nlohmann::ordered_json;

Json keys_vector()
{
  std::ifstream in(NAV2_PYIF_KEYS_VECTOR);
  if (!in) {
    throw std::runtime_error(std::string("cannot read ") + NAV2_PYIF_KEYS_VECTOR);
  }
  return Json::parse(in);
}

TEST(KeysVector, EveryKeyUnderAPrefixIsThePythonKeySpaces)
{
  const Json vector = keys_vector();
  const KeySpace keys(vector.at("prefix").get<std::string>());
  ASSERT_EQ(vector.at("calls").size(), proto::kOpCount);
  for (const auto & [op_name, key] : vector.at("calls").items()) {
    const auto op = proto::op_from_name(op_name);
    ASSERT_TRUE(op.has_value()) << op_name;
    EXPECT_EQ(keys.call(*op), key.get<std::string>()) << op_name;
  }
  EXPECT_EQ(keys.cancel(), vector.at("cancel").get<std::string>());
  EXPECT_EQ(keys.hosts(), vector.at("hosts").get<std::string>());
  const std::string host = vector.at("host_token").at("host").get<std::string>();
  const std::string token = vector.at("host_token").at("key").get<std::string>();
  EXPECT_EQ(KeySpace::host_id_of(token), host);
}

TEST(KeysVector, APrefixIsRefusedWithThePythonMessageOrAccepted)
{
  const Json vector = keys_vector();
  ASSERT_FALSE(vector.at("prefixes").empty());
  for (const auto & entry : vector.at("prefixes")) {
    const std::string prefix = entry.at("prefix").get<std::string>();
    if (entry.at("refused").is_null()) {
      EXPECT_NO_THROW(validate_prefix(prefix)) << prefix;
      continue;
    }
    try {
      validate_prefix(prefix);
      ADD_FAILURE() << "accepted '" << prefix << "'";
    } catch (const std::invalid_argument & error) {
      EXPECT_EQ(std::string(error.what()), entry.at("refused").get<std::string>());
    }
  }
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
