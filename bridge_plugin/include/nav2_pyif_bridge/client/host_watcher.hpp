// Which planner hosts are alive on a key prefix, from their liveliness tokens P/host/<id>.
// Fed by a liveliness *subscriber with history* (not a liveliness get: with the zenoh-pico
// backend a get matching several tokens breaks the session), as the reference client's
// HostWatcher is. Thread-safe: Zenoh calls on_token from its own threads.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <string_view>

#include "nav2_pyif_bridge/client/clock.hpp"

namespace nav2_pyif_bridge::client
{

class HostWatcher
{
public:
  using Hosts = std::set<std::string, std::less<>>;
  // Called after each change, outside the watcher's lock: (host id, alive).
  using OnChange = std::function<void (const std::string &, bool)>;

  explicit HostWatcher(Clock & clock = SteadyClock::instance(), OnChange on_change = {});

  // A liveliness sample for P/host/<host_id>: alive for PUT, not alive for DELETE.
  void on_token(std::string_view host_id, bool alive);

  bool any_alive() const;
  Hosts alive() const;
  // How many times the set of hosts changed (a new host, or one gone).
  std::size_t changes() const;

  // The clock its waits run on (a fake one in the unit tests).
  Clock & clock() const {return clock_;}

  // Block until at least one host is alive; false when `timeout` passed first.
  bool wait_for_any(Duration timeout);
  // Block until `predicate(alive hosts)` holds; false when `timeout` passed first.
  bool wait_until(const std::function<bool(const Hosts &)> & predicate, Duration timeout);

private:
  Clock & clock_;
  OnChange on_change_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Hosts alive_;
  std::size_t changes_{0};
};

}  // namespace nav2_pyif_bridge::client
