// Generated from protocol/nav2_pyif_protocol/bridge_params.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// The Nav2 plugin's own parameters (bridge_params.py's table; bridge_plugin/README.md's parameter
// table): every other parameter under the plugin's namespace goes to the planner. Read by
// settings.cpp (split_parameters) and plugin_bridge.cpp (ros2 param set).

#pragma once

#include <array>
#include <chrono>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nav2_pyif_bridge/client/clock.hpp"
#include "nav2_pyif_bridge/protocol/ops.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"

namespace nav2_pyif_bridge::client
{

// A parameter's value as the bridge reads it (settings.cpp). Each throws std::invalid_argument
// naming the parameter for another type: a string; a string or a list of strings; seconds, a number
// > 0.
std::string string_parameter(std::string_view name, const protocol::ParamValue & value);
std::vector<std::string> strings_parameter(
  std::string_view name, const protocol::ParamValue & value);
Duration seconds_parameter(std::string_view name, const protocol::ParamValue & value);

// How long to wait for a reply, by timeout class (PROTOCOL.md section 8): which one bounds an op is
// schema.py's OP_TIMEOUT (protocol::timeout_class).
struct Timeouts
{
  Duration call{std::chrono::milliseconds(40)};  // timeout
  Duration lifecycle{std::chrono::seconds(5)};  // lifecycle_timeout
  Duration configure{std::chrono::seconds(10)};  // configure_timeout
  Duration plan{std::chrono::seconds(5)};  // plan_timeout

  Duration for_op(protocol::Op op) const noexcept
  {
    switch (protocol::timeout_class(op)) {
      case protocol::TimeoutClass::Call:
        return call;
      case protocol::TimeoutClass::Lifecycle:
        return lifecycle;
      case protocol::TimeoutClass::Configure:
        return configure;
      case protocol::TimeoutClass::Plan:
        return plan;
    }
    return call;
  }
};

inline constexpr Duration kWaitForHostDefault{std::chrono::seconds(5)};
inline constexpr Duration kLocalHostWaitForHost{std::chrono::seconds(60)};

struct BridgeParameters
{
  // Zenoh key prefix the planner host serves (e.g. nav2_pyif/robot1/FollowPath); with a local host,
  // optional
  std::string key;
  // Zenoh JSON5 config file (zenoh-c backend only); unset: $NAV2_PYIF_ZENOH_CONFIG, else the
  // package's shipped config/default_session.json5
  std::string zenoh_config;
  // endpoints to connect to (a router, or a host started with --listen), replacing the config
  // file's
  std::vector<std::string> zenoh_connect;
  // how long configure waits for a host; without one, Nav2 comes up anyway and the first call
  // configures the planner
  std::optional<Duration> wait_for_host;  // unset: kWaitForHostDefault
  // the function-delegate style: the plugin starts and supervises its own planner-host for this
  // module of functions (--module)
  std::string python_module;
  // its role -> function map, given to the host as --delegate items (["role=function", ...], one
  // "r=f,r2=f2" string, or nested python_delegates.<role>: function); without it, the module's
  // functions named after the roles
  std::vector<std::string> python_delegates;
  // or a planner class, module:Class, for the local host (--planner)
  std::string python_planner;
  // where the local host imports planners from (--path)
  std::vector<std::string> python_path;
  // the executable that runs the local host
  std::string planner_host_command{"planner-host"};
  // more arguments for the local host (e.g. ["--isolation", "none"])
  std::vector<std::string> planner_host_args;
  // controllers: extra topics (e.g. ["scan"] with scan.topic: /scan, scan.type:
  // sensor_msgs/msg/LaserScan), subscribed on controller_server's node; the latest message of each
  // goes with the next call, serialized, only when new; the planner reads self.inputs["scan"]
  std::vector<std::string> inputs;
  // timeout, configure_timeout, plan_timeout, lifecycle_timeout
  Timeouts timeouts;
};

// Each name the bridge reads (aliases included) and whether `ros2 param set` may change it on a
// running plugin (else it is read at configure).
struct BridgeParameterName
{
  std::string_view name;
  bool live;
};
inline constexpr std::array<BridgeParameterName, 16> kBridgeParameters = {{
  {"key", false},
  {"zenoh_config", false},
  {"zenoh_connect", false},
  {"timeout", true},
  {"configure_timeout", true},
  {"plan_timeout", true},
  {"lifecycle_timeout", true},
  {"wait_for_host", true},
  {"python_module", false},
  {"python_delegates", false},
  {"python_planner", false},
  {"python_path", false},
  {"planner_host_command", false},
  {"planner_host_executable", false},
  {"planner_host_args", false},
  {"inputs", false},
}};

// Set the member `name` names (a timeout: its class in `timeouts`) from `value`; false when `name`
// is none of the bridge's. Throws std::invalid_argument naming the parameter for a value of the
// wrong type.
inline bool set_bridge_parameter(
  BridgeParameters & out, std::string_view name, const protocol::ParamValue & value)
{
  if (name == "key") {
    out.key = string_parameter(name, value);
  } else if (name == "zenoh_config") {
    out.zenoh_config = string_parameter(name, value);
  } else if (name == "zenoh_connect") {
    out.zenoh_connect = strings_parameter(name, value);
  } else if (name == "timeout") {
    out.timeouts.call = seconds_parameter(name, value);
  } else if (name == "configure_timeout") {
    out.timeouts.configure = seconds_parameter(name, value);
  } else if (name == "plan_timeout") {
    out.timeouts.plan = seconds_parameter(name, value);
  } else if (name == "lifecycle_timeout") {
    out.timeouts.lifecycle = seconds_parameter(name, value);
  } else if (name == "wait_for_host") {
    out.wait_for_host = seconds_parameter(name, value);
  } else if (name == "python_module") {
    out.python_module = string_parameter(name, value);
  } else if (name == "python_delegates") {
    out.python_delegates = strings_parameter(name, value);
  } else if (name == "python_planner") {
    out.python_planner = string_parameter(name, value);
  } else if (name == "python_path") {
    out.python_path = strings_parameter(name, value);
  } else if (name == "planner_host_command" || name == "planner_host_executable") {
    out.planner_host_command = string_parameter(name, value);
  } else if (name == "planner_host_args") {
    out.planner_host_args = strings_parameter(name, value);
  } else if (name == "inputs") {
    out.inputs = strings_parameter(name, value);
  } else {
    return false;
  }
  return true;
}

}  // namespace nav2_pyif_bridge::client
