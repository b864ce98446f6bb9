// The plugin's YAML parameters (everything under its namespace, e.g. FollowPath.*): the
// bridge's own settings, and the rest, forwarded to the planner in configure.
//
//   key                 Zenoh key prefix P the planner host serves (nav2_pyif/robot1/FollowPath)
//   zenoh_config        Zenoh JSON5 config file (zenoh-c backend); default
//                       $NAV2_PYIF_ZENOH_CONFIG, else a client of tcp/localhost:7447
//   zenoh_connect       endpoints to connect to (string or list), overriding the file's
//   timeout             [s] compute_velocity_commands, set_plan, set_speed_limit, cancel (0.04)
//   configure_timeout   [s] configure (10.0)
//   plan_timeout        [s] create_plan (5.0)
//   lifecycle_timeout   [s] activate, deactivate, cleanup, set_parameters, reset (5.0)
//   wait_for_host       [s] how long configure waits for a host to appear (5.0; 60.0 for a
//                       local host); without one, configure is deferred to the first call
//   python_module       the function-delegate style: a module of functions ...
//   python_delegates    ... and its role -> function map: ["role=function", ...], one
//                       "r1=f1,r2=f2" string, or nested python_delegates.<role>: function
//   python_planner      or a planner class, module:Class
//   python_path         directories to import planners from (planner-host --path)
//   planner_host_command  the planner-host executable (default: planner-host on PATH)
//   planner_host_args   more arguments for it (e.g. ["--isolation", "none"])
//   inputs              extra topics for the controller, Nav2 style: ["scan"] with
//                       scan.topic: "/scan" and scan.type: "sensor_msgs/msg/LaserScan"
//
// With python_module or python_planner the plugin starts and supervises its own planner host
// (local_host.hpp) and connects to it directly; `key` is then optional.
// `plugin` (Nav2's) and the names above are not forwarded; every other parameter is.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nav2_pyif_bridge/client/plugin_session.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"

namespace nav2_pyif_bridge::client
{

// What a local planner host serves and how it is started.
struct LocalHostSpec
{
  std::string command{"planner-host"};
  std::string planner;  // module:Class
  std::string module;   // module of functions ...
  std::vector<std::pair<std::string, std::string>> delegates;  // ... role -> function
  std::vector<std::string> paths;
  std::vector<std::string> extra_args;

  bool enabled() const noexcept {return !planner.empty() || !module.empty();}
};

// One of a controller's extra input topics (the `inputs` parameter).
struct InputSpec
{
  std::string name;   // the planner's self.inputs[name]
  std::string topic;  // subscribed on the server's node
  std::string type;   // package/msg/Type
};

struct BridgeSettings
{
  std::string key;  // empty with a local host: the plugin chooses one
  std::string zenoh_config;
  std::vector<std::string> zenoh_connect;
  Timeouts timeouts;
  std::optional<Duration> wait_for_host;  // unset: 5 s, or 60 s with a local host
  LocalHostSpec local_host;
  std::vector<InputSpec> inputs;

  Duration host_wait() const;
};

struct PluginParameters
{
  BridgeSettings settings;
  protocol::Params forwarded;  // to the planner, in configure
};

// The bridge's own parameter names (and `plugin`), which are not forwarded.
bool is_bridge_parameter(std::string_view name) noexcept;

// "FollowPath.max_vel_x" -> "max_vel_x" for plugin "FollowPath"; std::nullopt for a name
// outside the plugin's namespace.
std::optional<std::string> plugin_parameter_name(std::string_view full_name, std::string_view plugin);

// A duration parameter in seconds (a float or an int, > 0). Throws std::invalid_argument.
Duration seconds_parameter(std::string_view name, const protocol::ParamValue & value);

// Split the plugin's parameters (names without the plugin prefix). Throws
// std::invalid_argument naming the parameter for a wrong type or value, a missing key, ...
PluginParameters split_parameters(const protocol::Params & params);

// ["compute_velocity_commands=compute", "set_plan=a,reset=b"] -> ordered (role, function)
// pairs; a bare "role" means a function of the same name. Throws std::invalid_argument.
std::vector<std::pair<std::string, std::string>> parse_delegates(
  const std::vector<std::string> & items);

}  // namespace nav2_pyif_bridge::client
