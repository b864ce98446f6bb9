// The Zenoh rows of the C++-client cycle bench, each on the plugin's own code: ZenohTransport
// (the plugin's get with a timeout) and ControllerSession (sid/epoch/seq, the call procedure,
// the codec, the costmap-version check, the command check).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/client/costmap_version.hpp"
#include "nav2_pyif_bridge/client/transport.hpp"
#include "nav2_pyif_bridge/zenoh_transport.hpp"

#include "sample.hpp"

namespace nav2_pyif_bench
{

namespace client = nav2_pyif_bridge::client;
namespace protocol = nav2_pyif_bridge::protocol;

// Passes every call to `inner`, keeping the last reply and how long its query took, so a
// cycle's Zenoh round trip can be told apart from the client's own work. The copy of a reply
// of about a hundred bytes is all it adds to the timed path.
class TimedTransport : public client::Transport
{
public:
  explicit TimedTransport(client::Transport & inner)
  : inner_(inner) {}

  std::optional<protocol::Bytes> query(
    const client::Target & target, const protocol::Bytes & payload, client::Duration timeout,
    const client::WaitHook * hook) override;
  void send(
    const client::Target & target, const protocol::Bytes & payload,
    client::Duration timeout) override
  {
    inner_.send(target, payload, timeout);
  }
  client::HostWatcher & hosts() override {return inner_.hosts();}

  std::int64_t last_query_ns() const noexcept {return last_query_ns_;}
  const protocol::Bytes & last_reply() const noexcept {return last_reply_;}

private:
  client::Transport & inner_;
  std::int64_t last_query_ns_{-1};
  protocol::Bytes last_reply_;
};

// The costmap the sessions send: a fixed 10 x 10 grid, as protocol_bench's costmap(10). Read
// through the real CostmapVersion every cycle, as the plugin reads Nav2's costmap.
class FixedCostmap : public client::CostmapSource
{
public:
  FixedCostmap();
  client::CostmapRead read(std::optional<std::uint64_t> known) override;

private:
  std::vector<std::uint8_t> cells_;
  client::CostmapVersion version_;
};

// A ControllerSession on its own Zenoh session to a planner host listening at `endpoint`.
class PyifCycle
{
public:
  PyifCycle(const std::string & endpoint, const std::string & key, client::Logger logger);

  // Wait for the host, then configure, activate and set a short plan. Throws on failure.
  void start(client::Duration wait_for_host);
  // One compute_velocity_commands (PoseStamped + Twist in, TwistStamped out).
  Sample cycle();
  // One set_plan of a 1000-pose plan (protocol's plan row): the plan path as Nav2 sends it,
  // every pose and the goal encoded, sent and decoded into the planner's NumPy array.
  Sample plan();
  // The host's cheapest reply: an activate of a session it does not know (SessionUnknown),
  // the host's fixed cost per query without planner or message work.
  Sample unknown_session();
  void stop();

private:
  // `call` timed whole, its Zenoh get, and the host's compute_ns from the reply to `op`.
  template<class Call>
  Sample timed(protocol::Op op, Call && call);

  client::KeySpace keys_;
  nav2_pyif_bridge::ZenohTransport zenoh_;
  TimedTransport timed_;
  FixedCostmap costmap_;
  client::ControllerSession session_;
  protocol::PoseStamped pose_;
  protocol::Path long_plan_;
  protocol::Bytes unknown_request_;
};

// The floor: the plugin's Zenoh get to a bare queryable replying an empty payload.
class BareGet
{
public:
  BareGet(const std::string & endpoint, const std::string & key, client::Logger logger);

  // Retry until the queryable answers (it has no liveliness token under P/host/*).
  void start(client::Duration wait);
  Sample get();

private:
  std::string key_;
  nav2_pyif_bridge::ZenohTransport zenoh_;
};

}  // namespace nav2_pyif_bench
