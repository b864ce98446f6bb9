// libFuzzer harness: plugin parameters and settings. The bytes are read as a request (the
// params of configure and set_parameters, as the host receives them) or, failing that, as a
// bare msgpack params map (reader.hpp's read_params); either way the map goes through
// split_parameters, as a plugin's YAML parameters do. Seeds: protocol/vectors.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>

#include "fuzz_check.hpp"
#include "nav2_pyif_bridge/client/settings.hpp"
#include "parse.hpp"
#include "reader.hpp"

namespace protocol = nav2_pyif_bridge::protocol;
namespace client = nav2_pyif_bridge::client;
using nav2_pyif_bridge::fuzz::broken;

namespace
{

// The split keeps the bridge's parameters and forwards the rest, each under its own name.
void split(const protocol::Params & params)
{
  for (const auto & [name, value] : params) {
    const auto local = client::plugin_parameter_name("FollowPath." + name, "FollowPath");
    if (!name.empty() && local != name) {
      broken("plugin_parameter_name lost the parameter '" + name + "'");
    }
    (void)client::is_live_parameter(name);
  }
  client::PluginParameters split;
  try {
    split = client::split_parameters(params);
  } catch (const std::invalid_argument &) {
    return;  // a parameter the plugin refuses, named in the message
  }
  for (const auto & [name, value] : split.forwarded) {
    if (client::is_bridge_parameter(name)) {
      broken("the bridge's own parameter '" + name + "' was forwarded to the planner");
    }
  }
  if (!client::starts_local_host(split.settings) && split.settings.key.empty()) {
    broken("settings accepted with neither a key nor a local host");
  }
  (void)client::host_wait(split.settings);
}

bool split_request_params(const std::uint8_t * data, std::size_t size)
{
  protocol::Request request;
  try {
    request = protocol::decode_request(data, size);
  } catch (const protocol::DecodeError &) {
    return false;
  }
  if (const auto * configure = std::get_if<protocol::ConfigureRequest>(&request.body)) {
    split(configure->params);
    if (configure->nav2_params) {
      split(*configure->nav2_params);
    }
  } else if (const auto * set = std::get_if<protocol::SetParametersRequest>(&request.body)) {
    split(set->params);
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  if (split_request_params(data, size)) {
    return 0;
  }
  namespace detail = protocol::detail;
  try {
    const detail::ParsedMessage parsed(data, size, "params");
    split(detail::read_params(parsed.root(), detail::FieldPath("params")));
  } catch (const protocol::DecodeError &) {
  }
  return 0;
}
