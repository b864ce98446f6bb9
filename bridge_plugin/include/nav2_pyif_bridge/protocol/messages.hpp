// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// The envelopes (PROTOCOL.md section 13, "Envelopes"): what one Zenoh query carries (Request) and
// what its reply carries (Reply), with the op's body. Encode and decode them with codec.hpp.

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
  // protocol version
  std::int64_t v{kProtocolVersion};
  // session id chosen by the client at configure
  std::string sid;
  // session epoch: 1 at the first configure, +1 at each re-establishment
  std::uint64_t epoch{1};
  // per-plugin sequence number, strictly increasing across epochs
  std::uint64_t seq{0};
  // operation-specific map
  RequestBody body;

  // operation (also the last key chunk): the op of the body's type, so that the wire's `op` and the
  // body never disagree.
  Op op() const noexcept {return op_of(body);}
};

struct Reply
{
  // protocol version
  std::int64_t v{kProtocolVersion};
  // the request's seq
  std::uint64_t seq{0};
  // The wire's `ok` with either `body` (true) or `error` (false): one of them, never both.
  std::variant<ReplyBody, Error> outcome;
  // id of the host that answered
  std::string host;
  // time spent in the planner's method [ns]; 0 when not called
  std::int64_t compute_ns{0};

  // true: body follows; false: error follows
  bool ok() const noexcept {return outcome.index() == 0;}
  // Throw std::bad_variant_access when called on the other kind of reply.
  const ReplyBody & body() const {return std::get<0>(outcome);}
  const Error & error() const {return std::get<1>(outcome);}
};

}  // namespace nav2_pyif_bridge::protocol
