#include "nav2_pyif_bridge/client/keys.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace nav2_pyif_bridge::client
{

void validate_prefix(std::string_view prefix)
{
  const std::string quoted = "key prefix '" + std::string(prefix) + "'";
  if (prefix.empty() || prefix.front() == '/' || prefix.back() == '/') {
    throw std::invalid_argument(quoted + " must be non-empty without leading/trailing '/'");
  }
  std::size_t start = 0;
  while (start <= prefix.size()) {
    const std::size_t end = std::min(prefix.find('/', start), prefix.size());
    const std::string_view chunk = prefix.substr(start, end - start);
    if (chunk.empty() || chunk.find_first_of("*$?#") != std::string_view::npos) {
      throw std::invalid_argument(
              quoted + " has an empty or wildcard chunk '" + std::string(chunk) + "'");
    }
    if (chunk.front() == '@') {
      throw std::invalid_argument(
              quoted + ": chunk '" + std::string(chunk) + "' starts with '@', reserved by Zenoh "
              "('@/' admin space) and rmw_zenoh ('@ros2_lv/' liveliness)");
    }
    start = end + 1;
  }
  // rmw_zenoh keys topics and services <ROS domain id>/...: a prefix that starts with a number
  // could meet ROS traffic on a router both use.
  const std::string_view first = prefix.substr(0, prefix.find('/'));
  if (std::all_of(first.begin(), first.end(), [](char c) {return c >= '0' && c <= '9';})) {
    throw std::invalid_argument(
            quoted + " starts with a number: rmw_zenoh's topics and services are keyed "
            "<ROS domain id>/..., so a prefix like that could meet ROS traffic on a shared "
            "router; start it with a name (e.g. nav2_pyif/...)");
  }
}

KeySpace::KeySpace(std::string prefix)
: prefix_(std::move(prefix))
{
  validate_prefix(prefix_);
}

std::string KeySpace::call(protocol::Op op) const
{
  if (op == protocol::Op::CancelPlan) {
    return cancel();
  }
  return prefix_ + "/rpc/" + std::string(protocol::op_name(op));
}

std::string_view KeySpace::host_id_of(std::string_view token_key) noexcept
{
  const std::size_t slash = token_key.rfind('/');
  return slash == std::string_view::npos ? token_key : token_key.substr(slash + 1);
}

}  // namespace nav2_pyif_bridge::client
