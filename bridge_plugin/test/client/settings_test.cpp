// The plugin's YAML parameters: bridge settings apart, everything else forwarded.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/settings.hpp"

namespace nav2_pyif_bridge::client
{
namespace
{

namespace proto = protocol;
using namespace std::chrono_literals;
using Pairs = std::vector<std::pair<std::string, std::string>>;

std::string error_of(const proto::Params & params)
{
  try {
    split_parameters(params);
  } catch (const std::invalid_argument & e) {
    return e.what();
  }
  return "no error";
}

TEST(Settings, SplitsBridgeSettingsFromForwardedParameters)
{
  proto::Params p;
  p.set("plugin", std::string("nav2_pyif_bridge::PyController"));
  p.set("key", std::string("nav2_pyif/robot1/FollowPath"));
  p.set("timeout", 0.05);
  p.set("configure_timeout", std::int64_t{20});
  p.set("plan_timeout", 2.5);
  p.set("lifecycle_timeout", 1.0);
  p.set("wait_for_host", 3.0);
  p.set("zenoh_connect", std::vector<std::string>{"tcp/10.0.0.2:7447"});
  p.set("max_vel_x", 0.5);
  p.set("critics.weight", std::int64_t{3});
  p.set("names", std::vector<std::string>{"a", "b"});
  const PluginParameters out = split_parameters(p);
  const BridgeSettings & s = out.settings;
  EXPECT_EQ(s.key, "nav2_pyif/robot1/FollowPath");
  EXPECT_EQ(s.timeouts.call, Duration{50ms});
  EXPECT_EQ(s.timeouts.configure, Duration{20s});
  EXPECT_EQ(s.timeouts.plan, Duration{2500ms});
  EXPECT_EQ(s.timeouts.lifecycle, Duration{1s});
  EXPECT_EQ(s.host_wait(), Duration{3s});
  EXPECT_EQ(s.zenoh_connect, (std::vector<std::string>{"tcp/10.0.0.2:7447"}));
  EXPECT_FALSE(s.local_host.enabled());
  ASSERT_EQ(out.forwarded.size(), 3u);
  auto it = out.forwarded.begin();
  EXPECT_EQ((it++)->first, "max_vel_x");
  EXPECT_EQ((it++)->first, "critics.weight");
  EXPECT_EQ(it->first, "names");
}

TEST(Settings, Defaults)
{
  proto::Params p;
  p.set("key", std::string("k/FollowPath"));
  const BridgeSettings s = split_parameters(p).settings;
  EXPECT_EQ(s.timeouts.call, Duration{40ms});
  EXPECT_EQ(s.timeouts.configure, Duration{10s});
  EXPECT_EQ(s.timeouts.plan, Duration{5s});
  EXPECT_EQ(s.timeouts.lifecycle, Duration{5s});
  EXPECT_EQ(s.host_wait(), Duration{5s});
  EXPECT_TRUE(s.zenoh_config.empty());
  EXPECT_TRUE(s.zenoh_connect.empty());
}

TEST(Settings, SeedPaperStyleStartsALocalHost)
{
  proto::Params p;
  p.set("python_module", std::string("nav2_pyif_planners.apf"));
  p.set("python_delegates", std::vector<std::string>{
    "configure=configure", "compute_velocity_commands=compute_velocity_commands,set_plan"});
  p.set("python_path", std::string("/opt/planners"));
  const BridgeSettings s = split_parameters(p).settings;
  EXPECT_TRUE(s.local_host.enabled());
  EXPECT_TRUE(s.key.empty());
  EXPECT_EQ(s.local_host.module, "nav2_pyif_planners.apf");
  EXPECT_EQ(s.local_host.delegates, (Pairs{{"configure", "configure"},
    {"compute_velocity_commands", "compute_velocity_commands"}, {"set_plan", "set_plan"}}));
  EXPECT_EQ(s.local_host.paths, (std::vector<std::string>{"/opt/planners"}));
  EXPECT_EQ(s.host_wait(), Duration{60s});
  EXPECT_EQ(s.local_host.command, "planner-host");
}

TEST(Settings, DelegatesAsNestedParameters)
{
  proto::Params p;
  p.set("python_module", std::string("apf"));
  p.set("python_delegates.compute_velocity_commands", std::string("compute"));
  p.set("python_delegates.set_plan", std::string("plan"));
  p.set("gain", 1.0);
  const PluginParameters out = split_parameters(p);
  EXPECT_EQ(out.settings.local_host.delegates,
    (Pairs{{"compute_velocity_commands", "compute"}, {"set_plan", "plan"}}));
  EXPECT_EQ(out.forwarded.size(), 1u);
  EXPECT_TRUE(is_bridge_parameter("python_delegates.set_plan"));
}

TEST(Settings, PlannerClassStyle)
{
  proto::Params p;
  p.set("python_planner", std::string("my_pkg.ctrl:MyController"));
  p.set("key", std::string("nav2_pyif/r/FollowPath"));
  p.set("planner_host_args", std::vector<std::string>{"--isolation", "none"});
  const BridgeSettings s = split_parameters(p).settings;
  EXPECT_EQ(s.local_host.planner, "my_pkg.ctrl:MyController");
  EXPECT_EQ(s.key, "nav2_pyif/r/FollowPath");
  EXPECT_EQ(s.local_host.extra_args, (std::vector<std::string>{"--isolation", "none"}));
}

TEST(Settings, ErrorsNameTheParameter)
{
  EXPECT_NE(error_of({}).find("parameter key: missing"), std::string::npos);
  proto::Params p;
  p.set("key", std::string("a//b"));
  EXPECT_NE(error_of(p).find("parameter key: key prefix 'a//b'"), std::string::npos);
  p.set("key", std::int64_t{3});
  EXPECT_EQ(error_of(p), "parameter key: expected a string, got int");
  p.set("key", std::string("a/b"));
  p.set("timeout", std::string("fast"));
  EXPECT_EQ(error_of(p), "parameter timeout: expected seconds (a number), got str");
  p.set("timeout", -1.0);
  EXPECT_NE(error_of(p).find("parameter timeout: expected seconds > 0"), std::string::npos);
  p.set("timeout", 0.04);
  p.set("python_module", std::string("m"));
  EXPECT_EQ(error_of(p), "no error");  // alone: the host binds the functions named by role
  p.set("python_delegates", std::vector<std::string>{"=f"});
  EXPECT_NE(error_of(p).find("not of the form role=function"), std::string::npos);
  p.set("python_delegates", std::vector<std::string>{"create_plan=f"});
  p.set("zenoh_connect", std::string("tcp/1.2.3.4:7447"));
  EXPECT_NE(error_of(p).find("starts a local planner host"), std::string::npos);

  proto::Params both;
  both.set("python_module", std::string("m"));
  both.set("python_planner", std::string("m:C"));
  EXPECT_NE(error_of(both).find("not both"), std::string::npos);
  proto::Params no_class;
  no_class.set("python_planner", std::string("m"));
  EXPECT_NE(error_of(no_class).find("expected module:Class"), std::string::npos);
}

TEST(Settings, EmptyListsAreEmpty)
{
  proto::Params p;
  p.set("key", std::string("a/b"));
  p.set("zenoh_connect", std::vector<double>{});  // how an empty YAML list may arrive
  EXPECT_TRUE(split_parameters(p).settings.zenoh_connect.empty());
}

TEST(Settings, PluginParameterNames)
{
  EXPECT_EQ(plugin_parameter_name("FollowPath.max_vel_x", "FollowPath"), "max_vel_x");
  EXPECT_EQ(plugin_parameter_name("FollowPath.a.b", "FollowPath"), "a.b");
  EXPECT_EQ(plugin_parameter_name("FollowPathX.a", "FollowPath"), std::nullopt);
  EXPECT_EQ(plugin_parameter_name("FollowPath", "FollowPath"), std::nullopt);
  EXPECT_EQ(plugin_parameter_name("FollowPath.", "FollowPath"), std::nullopt);
  EXPECT_EQ(plugin_parameter_name("controller_frequency", "FollowPath"), std::nullopt);
  EXPECT_TRUE(is_bridge_parameter("plugin"));
  EXPECT_TRUE(is_bridge_parameter("timeout"));
  EXPECT_FALSE(is_bridge_parameter("max_vel_x"));
}

TEST(Settings, DelegatesParsing)
{
  EXPECT_EQ(parse_delegates({"a=f, b = g", "c"}), (Pairs{{"a", "f"}, {"b", "g"}, {"c", "c"}}));
  EXPECT_EQ(parse_delegates({"a=f", "a=g"}), (Pairs{{"a", "g"}}));  // the last one wins
  EXPECT_TRUE(parse_delegates({"", " , "}).empty());
  EXPECT_THROW(parse_delegates({"a="}), std::invalid_argument);
}

}  // namespace
}  // namespace nav2_pyif_bridge::client
