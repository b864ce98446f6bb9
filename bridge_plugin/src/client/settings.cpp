#include "nav2_pyif_bridge/client/settings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "nav2_pyif_bridge/client/keys.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

namespace
{

constexpr std::string_view kDelegatesPrefix = "python_delegates.";

[[noreturn]] void bad(std::string_view name, const std::string & problem)
{
  throw std::invalid_argument("parameter " + std::string(name) + ": " + problem);
}

std::string type_name(const proto::ParamValue & value)
{
  static constexpr std::array<std::string_view, 8> kNames = {
    "bool", "int", "float", "str", "bool[]", "int[]", "float[]", "str[]"};
  return std::string(kNames[value.index()]);
}

// "scan.topic" -> ("scan", "topic"); std::nullopt for other names.
std::optional<std::pair<std::string, std::string>> input_part(const std::string & name)
{
  const std::size_t dot = name.rfind('.');
  if (dot == std::string::npos || dot == 0) {
    return std::nullopt;
  }
  std::string part = name.substr(dot + 1);
  if (part != "topic" && part != "type") {
    return std::nullopt;
  }
  return std::make_pair(name.substr(0, dot), std::move(part));
}

// The inputs listed in `inputs`, each with its topic and type; their `<name>.topic` and
// `<name>.type` leave `forwarded` (they are the bridge's, not the planner's).
std::vector<InputSpec> take_inputs(const std::vector<std::string> & names, proto::Params & forwarded)
{
  if (names.size() > proto::kMaxInputs) {
    bad(
      "inputs", "lists " + std::to_string(names.size()) + " inputs; a planner host keeps at most " +
      std::to_string(proto::kMaxInputs) + " per session");
  }
  std::vector<InputSpec> out;
  for (const std::string & name : names) {
    InputSpec spec{name, {}, {}};
    if (name.empty() || name.find('.') != std::string::npos) {
      bad("inputs", "'" + name + "' is not an input name (non-empty, without '.')");
    }
    for (const auto & [item, value] : forwarded) {
      const auto part = input_part(item);
      if (part && part->first == name) {
        (part->second == "topic" ? spec.topic : spec.type) = string_parameter(item, value);
      }
    }
    if (spec.topic.empty()) {
      bad(name + ".topic", "missing: the topic of input '" + name + "' (e.g. /scan)");
    }
    const std::size_t slash = spec.type.find("/msg/");
    if (slash == std::string::npos || slash == 0 || slash + 5 >= spec.type.size()) {
      bad(name + ".type", "expected package/msg/Type (e.g. sensor_msgs/msg/LaserScan), got '" +
        spec.type + "'");
    }
    for (const auto & other : out) {
      if (other.name == name) {
        bad("inputs", "'" + name + "' is listed twice");
      }
    }
    out.push_back(std::move(spec));
  }
  proto::Params rest;
  for (const auto & [item, value] : forwarded) {
    const auto part = input_part(item);
    const bool taken = part && std::any_of(
      out.begin(), out.end(), [&](const InputSpec & spec) {return spec.name == part->first;});
    if (!taken) {
      rest.set(item, value);
    }
  }
  forwarded = std::move(rest);
  return out;
}

}  // namespace

std::string string_parameter(std::string_view name, const proto::ParamValue & value)
{
  if (const auto * text = std::get_if<std::string>(&value)) {
    return *text;
  }
  bad(name, "expected a string, got " + type_name(value));
}

std::vector<std::string> strings_parameter(std::string_view name, const proto::ParamValue & value)
{
  if (const auto * text = std::get_if<std::string>(&value)) {
    return text->empty() ? std::vector<std::string>{} : std::vector<std::string>{*text};
  }
  if (const auto * list = std::get_if<std::vector<std::string>>(&value)) {
    return *list;
  }
  // An empty list of any type is empty (a YAML `[]` has no element type).
  const bool empty_list = std::visit(
    [](const auto & v) {
      if constexpr (std::is_arithmetic_v<std::decay_t<decltype(v)>>) {
        return false;
      } else {
        return v.empty();  // a string was taken above
      }
    }, value);
  if (empty_list) {
    return {};
  }
  bad(name, "expected a string or a list of strings, got " + type_name(value));
}

Duration seconds_parameter(std::string_view name, const proto::ParamValue & value)
{
  double seconds = 0.0;
  if (const auto * f = std::get_if<double>(&value)) {
    seconds = *f;
  } else if (const auto * i = std::get_if<std::int64_t>(&value)) {
    seconds = static_cast<double>(*i);
  } else {
    bad(name, "expected seconds (a number), got " + type_name(value));
  }
  if (!std::isfinite(seconds) || seconds <= 0.0 || seconds > 1e6) {
    bad(name, "expected seconds > 0, got " + std::to_string(seconds));
  }
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

bool starts_local_host(const BridgeParameters & settings) noexcept
{
  return !settings.python_planner.empty() || !settings.python_module.empty();
}

Duration host_wait(const BridgeParameters & settings) noexcept
{
  return settings.wait_for_host.value_or(
    starts_local_host(settings) ? kLocalHostWaitForHost : kWaitForHostDefault);
}

bool is_bridge_parameter(std::string_view name) noexcept
{
  return name == "plugin" || name.substr(0, kDelegatesPrefix.size()) == kDelegatesPrefix ||
         std::any_of(
    kBridgeParameters.begin(), kBridgeParameters.end(),
    [name](const BridgeParameterName & known) {return known.name == name;});
}

bool is_live_parameter(std::string_view name) noexcept
{
  return std::any_of(
    kBridgeParameters.begin(), kBridgeParameters.end(),
    [name](const BridgeParameterName & known) {return known.live && known.name == name;});
}

std::optional<std::string> plugin_parameter_name(
  std::string_view full_name, std::string_view plugin)
{
  if (full_name.size() <= plugin.size() + 1 || full_name.substr(0, plugin.size()) != plugin ||
    full_name[plugin.size()] != '.')
  {
    return std::nullopt;
  }
  return std::string(full_name.substr(plugin.size() + 1));
}

PluginParameters split_parameters(const proto::Params & params)
{
  PluginParameters out;
  BridgeParameters & s = out.settings;
  std::vector<std::string> nested_delegates;  // python_delegates.<role>: function
  for (const auto & [name, value] : params) {
    if (name.rfind(kDelegatesPrefix, 0) == 0) {
      nested_delegates.push_back(
        name.substr(kDelegatesPrefix.size()) + "=" + string_parameter(name, value));
    } else if (name != "plugin" && !set_bridge_parameter(s, name, value)) {
      out.forwarded.set(name, value);
    }
  }
  s.python_delegates.insert(
    s.python_delegates.end(), nested_delegates.begin(), nested_delegates.end());
  out.inputs = take_inputs(s.inputs, out.forwarded);

  // python_module alone: the host binds the module's functions named after the roles, so a
  // module written with those names needs no map (planner-host --module m).
  if (s.python_module.empty() && !s.python_delegates.empty()) {
    bad("python_delegates", "given without python_module");
  }
  if (starts_local_host(s)) {
    if (!s.zenoh_config.empty() || !s.zenoh_connect.empty()) {
      bad(
        s.python_module.empty() ? "python_planner" : "python_module",
        "starts a local planner host that the plugin connects to directly; remove "
        "zenoh_config / zenoh_connect, or run planner-host yourself and set key");
    }
  } else if (s.key.empty()) {
    bad("key", "missing: the Zenoh key prefix a planner host serves (e.g. "
      "nav2_pyif/robot1/FollowPath), or python_module (+ python_delegates) for a local host");
  }
  if (!s.key.empty()) {
    try {
      validate_prefix(s.key);
    } catch (const std::invalid_argument & error) {
      bad("key", error.what());
    }
  }
  return out;
}

}  // namespace nav2_pyif_bridge::client
