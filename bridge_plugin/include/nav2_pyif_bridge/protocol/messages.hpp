// The envelopes: what one Zenoh query carries (Request) and what its reply carries (Reply).
#pragma once

#include <cstdint>
#include <string>
#include <variant>

#include "nav2_pyif_bridge/protocol/bodies.hpp"
#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "nav2_pyif_bridge/protocol/ops.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::protocol
{

struct Request
{
  std::int64_t v{kProtocolVersion};
  std::string sid;          // session id: chosen by the plugin once (UUID4 hex)
  std::uint64_t epoch{1};   // 1 at the first configure, +1 at each re-establishment
  std::uint64_t seq{0};     // strictly increasing per plugin, echoed in the reply
  RequestBody body;

  // The wire's `op` follows from the body's type, so the two can never disagree.
  Op op() const noexcept {return op_of(body);}
};

struct Reply
{
  std::int64_t v{kProtocolVersion};
  std::uint64_t seq{0};  // the request's seq
  // The wire's `ok` with either `body` (ok) or `error` (failed): one of them, never both.
  std::variant<ReplyBody, Error> outcome;
  std::string host;            // id of the host that answered
  std::int64_t compute_ns{0};  // time spent in the planner's method; 0 when not called

  bool ok() const noexcept {return outcome.index() == 0;}
  // Throw std::bad_variant_access when called on the other kind of reply.
  const ReplyBody & body() const {return std::get<ReplyBody>(outcome);}
  const Error & error() const {return std::get<Error>(outcome);}
};

}  // namespace nav2_pyif_bridge::protocol
