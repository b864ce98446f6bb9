// What the plugin logic needs from Zenoh, as an interface: the Nav2 plugins use
// ZenohTransport (zenoh_transport.hpp, ament build only); the unit tests a fake host.
// One Transport serves one plugin instance, i.e. one key prefix P.
#pragma once

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "nav2_pyif_bridge/client/clock.hpp"
#include "nav2_pyif_bridge/client/host_watcher.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"

namespace nav2_pyif_bridge::client
{

// Where a query goes: a key and, among replicas serving P, the one host that should answer
// (PROTOCOL.md section 1, "Replicas"): sent as the selector parameter host=<id> with query
// target ALL; the other hosts drop it. An empty host: any host may answer.
struct Target
{
  std::string key;
  std::string host;

  // The selector's parameters: "host=<id>", or "" for any host.
  std::string parameters() const {return host.empty() ? std::string() : "host=" + host;}
};

// Work to do while a query waits for its reply (polling Nav2's cancel checker).
struct WaitHook
{
  Duration period{std::chrono::milliseconds(5)};
  std::function<void()> poll;
};

class Transport
{
public:
  virtual ~Transport() = default;

  // One query (a Zenoh get, target ALL) to `target` carrying `payload`: the payload of the
  // first successful reply, or std::nullopt when none arrived within `timeout`. When `hook`
  // is given, its poll() runs about every hook->period until then.
  virtual std::optional<protocol::Bytes> query(
    const Target & target, const protocol::Bytes & payload, Duration timeout,
    const WaitHook * hook = nullptr) = 0;

  // A query whose replies nobody waits for (cancel_plan: the call it cancels answers).
  virtual void send(const Target & target, const protocol::Bytes & payload, Duration timeout) = 0;

  // The planner hosts alive under P/host/*, fed by a liveliness subscriber with history.
  virtual HostWatcher & hosts() = 0;

  bool hosts_alive() {return hosts().any_alive();}
  // Block until a host is alive; false when `timeout` passed first.
  bool wait_for_host(Duration timeout) {return hosts().wait_for_any(timeout);}
};

}  // namespace nav2_pyif_bridge::client
