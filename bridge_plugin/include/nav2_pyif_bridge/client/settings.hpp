// The plugin's YAML parameters (everything under its namespace, e.g. FollowPath.*): the
// bridge's own, and the rest, forwarded to the planner in configure. With python_module or
// python_planner the plugin starts its own planner host (local_host.hpp) and
// connects to it directly; `key` is then optional. What the local host is given (module,
// delegates, planner) it validates itself. The bridge's own parameters (their names, types,
// defaults, docs) are one table: bridge_parameters.hpp, generated, and the bridge README's.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nav2_pyif_bridge/client/bridge_parameters.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"

namespace nav2_pyif_bridge::client
{

// One of a controller's extra input topics (the `inputs` parameter).
struct InputSpec
{
  std::string name;   // the planner's self.inputs[name]
  std::string topic;  // subscribed on the server's node
  std::string type;   // package/msg/Type
};

struct PluginParameters
{
  BridgeParameters settings;
  std::vector<InputSpec> inputs;  // `inputs`, each with its <name>.topic and <name>.type
  protocol::Params forwarded;  // to the planner, in configure
};

// python_module or python_planner: the plugin runs its own planner host.
bool starts_local_host(const BridgeParameters & settings) noexcept;
// wait_for_host, else its default (longer with a local host).
Duration host_wait(const BridgeParameters & settings) noexcept;

// The bridge's own parameter names (and Nav2's `plugin`), which are not forwarded.
bool is_bridge_parameter(std::string_view name) noexcept;
// One of them that `ros2 param set` may change on a running plugin.
bool is_live_parameter(std::string_view name) noexcept;

// "FollowPath.max_vel_x" -> "max_vel_x" for plugin "FollowPath"; std::nullopt for a name
// outside the plugin's namespace.
std::optional<std::string> plugin_parameter_name(std::string_view full_name, std::string_view plugin);

// Split the plugin's parameters (names without the plugin prefix). Throws
// std::invalid_argument naming the parameter for a wrong type or value, a missing key, ...
PluginParameters split_parameters(const protocol::Params & params);

}  // namespace nav2_pyif_bridge::client
