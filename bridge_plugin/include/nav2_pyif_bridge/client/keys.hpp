// The Zenoh key expressions under one plugin instance's prefix P, built in one place
// (PROTOCOL.md section 1; the Python side's nav2_pyif_protocol.keys).
#pragma once

#include <string>
#include <string_view>

#include "nav2_pyif_bridge/protocol/ops.hpp"

namespace nav2_pyif_bridge::client
{

// Throws std::invalid_argument unless `prefix` is non-empty, has no leading or trailing '/',
// and no empty or wildcard ('*', '$', '?', '#') chunk.
void validate_prefix(std::string_view prefix);

class KeySpace
{
public:
  // Throws std::invalid_argument (validate_prefix).
  explicit KeySpace(std::string prefix);

  const std::string & prefix() const noexcept {return prefix_;}
  // P/rpc/<op>; cancel_plan goes to P/cancel, which the host answers even while a call runs.
  std::string call(protocol::Op op) const;
  std::string cancel() const {return prefix_ + "/cancel";}
  // What a plugin's liveliness subscriber watches: P/host/*.
  std::string hosts() const {return prefix_ + "/host/*";}
  // The <host_id> of a token key P/host/<host_id>.
  static std::string_view host_id_of(std::string_view token_key) noexcept;

private:
  std::string prefix_;
};

}  // namespace nav2_pyif_bridge::client
