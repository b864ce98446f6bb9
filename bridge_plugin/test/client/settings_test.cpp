// The plugin's YAML parameters: bridge settings apart, everything else forwarded.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/settings.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"

namespace nav2_pyif_bridge::client
{
namespace
{

namespace proto = protocol;
using namespace std::chrono_literals;

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
  const BridgeParameters & s = out.settings;
  EXPECT_EQ(s.key, "nav2_pyif/robot1/FollowPath");
  EXPECT_EQ(s.timeouts.call, Duration{50ms});
  EXPECT_EQ(s.timeouts.configure, Duration{20s});
  EXPECT_EQ(s.timeouts.plan, Duration{2500ms});
  EXPECT_EQ(s.timeouts.lifecycle, Duration{1s});
  EXPECT_EQ(host_wait(s), Duration{3s});
  EXPECT_EQ(s.zenoh_connect, (std::vector<std::string>{"tcp/10.0.0.2:7447"}));
  EXPECT_FALSE(starts_local_host(s));
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
  const BridgeParameters s = split_parameters(p).settings;
  EXPECT_EQ(s.timeouts.call, Duration{40ms});
  EXPECT_EQ(s.timeouts.configure, Duration{10s});
  EXPECT_EQ(s.timeouts.plan, Duration{5s});
  EXPECT_EQ(s.timeouts.lifecycle, Duration{5s});
  EXPECT_EQ(host_wait(s), Duration{5s});
  EXPECT_TRUE(s.zenoh_config.empty());
  EXPECT_TRUE(s.zenoh_connect.empty());
}

TEST(Settings, AModuleWithDelegatesStartsALocalHost)
{
  proto::Params p;
  p.set("python_module", std::string("nav2_pyif_planners.apf"));
  p.set("python_delegates", std::vector<std::string>{
    "configure=configure", "compute_velocity_commands=compute_velocity_commands,set_plan"});
  p.set("python_path", std::string("/opt/planners"));
  const BridgeParameters s = split_parameters(p).settings;
  EXPECT_TRUE(starts_local_host(s));
  EXPECT_TRUE(s.key.empty());
  EXPECT_EQ(s.python_module, "nav2_pyif_planners.apf");
  // as given: the host parses and checks them (planner-host --delegate)
  EXPECT_EQ(s.python_delegates, (std::vector<std::string>{
    "configure=configure", "compute_velocity_commands=compute_velocity_commands,set_plan"}));
  EXPECT_EQ(s.python_path, (std::vector<std::string>{"/opt/planners"}));
  EXPECT_EQ(host_wait(s), Duration{60s});
  EXPECT_EQ(s.planner_host_command, "planner-host");
}

TEST(Settings, DelegatesAsNestedParameters)
{
  proto::Params p;
  p.set("python_module", std::string("apf"));
  p.set("python_delegates.compute_velocity_commands", std::string("compute"));
  p.set("python_delegates.set_plan", std::string("plan"));
  p.set("gain", 1.0);
  const PluginParameters out = split_parameters(p);
  EXPECT_EQ(out.settings.python_delegates,
    (std::vector<std::string>{"compute_velocity_commands=compute", "set_plan=plan"}));
  EXPECT_EQ(out.forwarded.size(), 1u);
  EXPECT_TRUE(is_bridge_parameter("python_delegates.set_plan"));
}

TEST(Settings, PlannerClassStyle)
{
  proto::Params p;
  p.set("python_planner", std::string("my_pkg.ctrl:MyController"));
  p.set("key", std::string("nav2_pyif/r/FollowPath"));
  p.set("planner_host_args", std::vector<std::string>{"--isolation", "none"});
  const BridgeParameters s = split_parameters(p).settings;
  EXPECT_EQ(s.python_planner, "my_pkg.ctrl:MyController");
  EXPECT_EQ(s.key, "nav2_pyif/r/FollowPath");
  EXPECT_EQ(s.planner_host_args, (std::vector<std::string>{"--isolation", "none"}));
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
  p.set("python_delegates", std::vector<std::string>{"create_plan=f"});
  p.set("zenoh_connect", std::string("tcp/1.2.3.4:7447"));
  EXPECT_NE(error_of(p).find("starts a local planner host"), std::string::npos);
  proto::Params no_module;
  no_module.set("python_planner", std::string("m:C"));
  no_module.set("python_delegates", std::string("a=f"));
  EXPECT_NE(error_of(no_module).find("given without python_module"), std::string::npos);
}

TEST(Settings, AtMostTheInputsAHostKeepsPerSession)
{
  proto::Params p;
  p.set("key", std::string("a/b"));
  std::vector<std::string> names;
  for (std::size_t i = 0; i <= proto::kMaxInputs; ++i) {
    names.push_back("in" + std::to_string(i));
    p.set(names.back() + ".topic", "/t" + std::to_string(i));
    p.set(names.back() + ".type", std::string("sensor_msgs/msg/Imu"));
  }
  p.set("inputs", names);
  EXPECT_NE(error_of(p).find("parameter inputs: lists 65 inputs"), std::string::npos);
  names.pop_back();
  p.set("inputs", names);
  EXPECT_EQ(error_of(p), "no error");
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
  EXPECT_TRUE(is_bridge_parameter("planner_host_executable"));  // an older name
  EXPECT_FALSE(is_bridge_parameter("max_vel_x"));
}

TEST(Settings, OnlyTheWaitsChangeLive)
{
  for (const char * name : {"timeout", "configure_timeout", "plan_timeout", "lifecycle_timeout",
      "wait_for_host"})
  {
    EXPECT_TRUE(is_live_parameter(name)) << name;
  }
  for (const char * name : {"key", "zenoh_connect", "python_module", "inputs", "max_vel_x"}) {
    EXPECT_FALSE(is_live_parameter(name)) << name;
  }
  BridgeParameters s;
  ASSERT_TRUE(set_bridge_parameter(s, "plan_timeout", 7.5));
  EXPECT_EQ(s.timeouts.plan, Duration{7500ms});
  EXPECT_FALSE(set_bridge_parameter(s, "max_vel_x", 1.0));
}

}  // namespace
}  // namespace nav2_pyif_bridge::client
