#include "nav2_pyif_bridge/client/settings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <stdexcept>
#include <variant>

#include "nav2_pyif_bridge/client/keys.hpp"

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

namespace
{

constexpr std::string_view kDelegatesPrefix = "python_delegates.";

constexpr std::array<std::string_view, 17> kBridgeNames = {
  "plugin", "key", "zenoh_config", "zenoh_connect", "timeout", "configure_timeout",
  "plan_timeout", "lifecycle_timeout", "wait_for_host", "python_module", "python_delegates",
  "python_planner", "python_path", "planner_host_command", "planner_host_args", "inputs",
  "planner_host_executable",
};

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

std::string as_string(std::string_view name, const proto::ParamValue & value)
{
  if (const auto * text = std::get_if<std::string>(&value)) {
    return *text;
  }
  bad(name, "expected a string, got " + type_name(value));
}

// A string or a list of strings (an empty list of any type is empty).
std::vector<std::string> as_strings(std::string_view name, const proto::ParamValue & value)
{
  if (const auto * text = std::get_if<std::string>(&value)) {
    return text->empty() ? std::vector<std::string>{} : std::vector<std::string>{*text};
  }
  if (const auto * list = std::get_if<std::vector<std::string>>(&value)) {
    return *list;
  }
  const bool empty_list = std::visit(
    [](const auto & v) {
      using T = std::decay_t<decltype(v)>;
      if constexpr (std::is_same_v<T, std::vector<bool>>|| std::is_same_v<T, std::vector<std::int64_t>>||
      std::is_same_v<T, std::vector<double>>)
      {
        return v.empty();
      } else {
        return false;
      }
    }, value);
  if (empty_list) {
    return {};
  }
  bad(name, "expected a string or a list of strings, got " + type_name(value));
}

}  // namespace

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

namespace
{

Duration as_seconds(std::string_view name, const proto::ParamValue & value)
{
  return seconds_parameter(name, value);
}

std::string trim(std::string_view text)
{
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) {
    return {};
  }
  const auto last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

}  // namespace

Duration BridgeSettings::host_wait() const
{
  if (wait_for_host) {
    return *wait_for_host;
  }
  return local_host.enabled() ? std::chrono::seconds(60) : std::chrono::seconds(5);
}

bool is_bridge_parameter(std::string_view name) noexcept
{
  for (const std::string_view bridge : kBridgeNames) {
    if (name == bridge) {
      return true;
    }
  }
  return name.substr(0, kDelegatesPrefix.size()) == kDelegatesPrefix;
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

std::vector<std::pair<std::string, std::string>> parse_delegates(
  const std::vector<std::string> & items)
{
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string & item : items) {
    std::size_t start = 0;
    while (start <= item.size()) {
      const std::size_t end = std::min(item.find(',', start), item.size());
      const std::string pair = trim(std::string_view(item).substr(start, end - start));
      start = end + 1;
      if (pair.empty()) {
        continue;
      }
      const std::size_t eq = pair.find('=');
      std::string role = trim(pair.substr(0, eq));
      std::string function = eq == std::string::npos ? role : trim(pair.substr(eq + 1));
      if (role.empty() || function.empty()) {
        throw std::invalid_argument(
                "parameter python_delegates: '" + pair + "' is not of the form role=function");
      }
      bool replaced = false;
      for (auto & existing : out) {
        if (existing.first == role) {
          existing.second = function;
          replaced = true;
        }
      }
      if (!replaced) {
        out.emplace_back(std::move(role), std::move(function));
      }
    }
  }
  return out;
}

namespace
{

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
  std::vector<InputSpec> out;
  for (const std::string & name : names) {
    InputSpec spec{name, {}, {}};
    if (name.empty() || name.find('.') != std::string::npos) {
      bad("inputs", "'" + name + "' is not an input name (non-empty, without '.')");
    }
    for (const auto & [item, value] : forwarded) {
      const auto part = input_part(item);
      if (part && part->first == name) {
        (part->second == "topic" ? spec.topic : spec.type) = as_string(item, value);
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

PluginParameters split_parameters(const proto::Params & params)
{
  PluginParameters out;
  BridgeSettings & s = out.settings;
  std::vector<std::string> delegate_items;
  std::vector<std::string> inputs;
  for (const auto & [name, value] : params) {
    if (name == "inputs") {
      inputs = as_strings(name, value);
    } else if (name == "key") {
      s.key = as_string(name, value);
    } else if (name == "zenoh_config") {
      s.zenoh_config = as_string(name, value);
    } else if (name == "zenoh_connect") {
      s.zenoh_connect = as_strings(name, value);
    } else if (name == "timeout") {
      s.timeouts.call = as_seconds(name, value);
    } else if (name == "configure_timeout") {
      s.timeouts.configure = as_seconds(name, value);
    } else if (name == "plan_timeout") {
      s.timeouts.plan = as_seconds(name, value);
    } else if (name == "lifecycle_timeout") {
      s.timeouts.lifecycle = as_seconds(name, value);
    } else if (name == "wait_for_host") {
      s.wait_for_host = as_seconds(name, value);
    } else if (name == "python_module") {
      s.local_host.module = as_string(name, value);
    } else if (name == "python_planner") {
      s.local_host.planner = as_string(name, value);
    } else if (name == "python_delegates") {
      for (auto & item : as_strings(name, value)) {
        delegate_items.push_back(std::move(item));
      }
    } else if (name.rfind(kDelegatesPrefix, 0) == 0) {
      delegate_items.push_back(
        name.substr(kDelegatesPrefix.size()) + "=" + as_string(name, value));
    } else if (name == "python_path") {
      s.local_host.paths = as_strings(name, value);
    } else if (name == "planner_host_command" || name == "planner_host_executable") {
      s.local_host.command = as_string(name, value);
    } else if (name == "planner_host_args") {
      s.local_host.extra_args = as_strings(name, value);
    } else if (name != "plugin") {
      out.forwarded.set(name, value);
    }
  }
  s.local_host.delegates = parse_delegates(delegate_items);
  s.inputs = take_inputs(inputs, out.forwarded);

  LocalHostSpec & local = s.local_host;
  if (!local.planner.empty() && !local.module.empty()) {
    bad("python_planner", "give either python_planner (module:Class) or python_module, not both");
  }
  // python_module alone: the host binds the module's functions named after the roles, so a
  // module written with those names needs no map (planner-host --module m).
  if (local.module.empty() && !local.delegates.empty()) {
    bad("python_delegates", "given without python_module");
  }
  if (!local.planner.empty() && local.planner.find(':') == std::string::npos) {
    bad("python_planner", "expected module:Class, got '" + local.planner + "'");
  }
  if (local.command.empty()) {
    bad("planner_host_command", "must not be empty");
  }
  if (local.enabled()) {
    if (!s.zenoh_config.empty() || !s.zenoh_connect.empty()) {
      bad(
        local.module.empty() ? "python_planner" : "python_module",
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
