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
    start = end + 1;
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

std::string KeySpace::host_token(std::string_view host_id) const
{
  return prefix_ + "/host/" + std::string(host_id);
}

std::string_view KeySpace::host_id_of(std::string_view token_key) noexcept
{
  const std::size_t slash = token_key.rfind('/');
  return slash == std::string_view::npos ? token_key : token_key.substr(slash + 1);
}

}  // namespace nav2_pyif_bridge::client
