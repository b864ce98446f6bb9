// What the plugin logic needs from Zenoh, as an interface: the Nav2 plugins use
// ZenohTransport (zenoh_transport.hpp, ament build only); the unit tests a fake host.
// One Transport serves one plugin instance, i.e. one key prefix P.
#pragma once

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "nav2_pyif_bridge/client/clock.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"

namespace nav2_pyif_bridge::client
{

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

  // One query (a Zenoh get) on `key` carrying `payload`: the payload of the first successful
  // reply, or std::nullopt when none arrived within `timeout`. When `hook` is given, its
  // poll() runs about every hook->period until then.
  virtual std::optional<protocol::Bytes> query(
    const std::string & key, const protocol::Bytes & payload, Duration timeout,
    const WaitHook * hook = nullptr) = 0;

  // A query whose replies nobody waits for (cancel_plan: the call it cancels answers).
  virtual void send(const std::string & key, const protocol::Bytes & payload, Duration timeout) = 0;

  // Whether a planner host's liveliness token is alive under P/host/*.
  virtual bool hosts_alive() = 0;

  // Block until a host is alive; false when `timeout` passed first.
  virtual bool wait_for_host(Duration timeout) = 0;
};

}  // namespace nav2_pyif_bridge::client
