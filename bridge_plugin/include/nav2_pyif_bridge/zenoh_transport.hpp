// The Transport over zenoh-cpp, on the subset both its backends share: Session::get with a
// timeout (target ALL, the host=<id> selector parameter), and a liveliness *subscriber with
// history* on P/host/* (never a liveliness get: with zenoh-pico a get matching several tokens
// breaks the session).
//
// Session configuration (as rmw_zenoh: a JSON5 file named by a parameter or an environment
// variable, a router on tcp/localhost:7447 by default):
//   - zenoh-c backend (ROS' zenoh_cpp_vendor): the file `zenoh_config`, else
//     $NAV2_PYIF_ZENOH_CONFIG, else the package's share/nav2_pyif_bridge/config/
//     default_session.json5 (a client of tcp/localhost:7447); `zenoh_connect` replaces the
//     file's connect endpoints.
//   - zenoh-pico backend (ZENOHCXX_ZENOHPICO): client mode only, configured by integer keys;
//     no JSON5 files (a `zenoh_config` is refused), one connect endpoint (the first).
// A session that cannot be opened (no router or host listening yet) is retried every second
// in the background; meanwhile no host is alive, so calls fail fast. A zenoh-pico session
// connected to nothing for 5 s is replaced by a new one (zenoh-pico's own reconnection can give
// up for good: zenoh_transport.cpp says when).
// Sessions are shared between the plugins of one process that use the same configuration, and
// live as long as the process (closing a zenoh-pico session whose peer went away can block).
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "nav2_pyif_bridge/client/keys.hpp"
#include "nav2_pyif_bridge/client/log.hpp"
#include "nav2_pyif_bridge/client/transport.hpp"

namespace zenoh
{
class Session;
}

namespace nav2_pyif_bridge
{

struct ZenohOptions
{
  std::string config_file;           // JSON5 (zenoh-c only); empty: $NAV2_PYIF_ZENOH_CONFIG
  std::vector<std::string> connect;  // empty: the file's
  // The Nav2 server whose plugins share one session. In a composed container every server
  // is in one process: a planner's costmap on a shared zenoh-pico session queued the
  // controller's 40 ms queries behind it. Empty: shared by the whole process.
  std::string owner;
};

// "zenoh-c" or "zenoh-pico": the backend this package was built with.
const char * zenoh_backend() noexcept;

class ZenohTransport : public client::Transport
{
public:
  // Throws std::invalid_argument for options this backend cannot honour.
  ZenohTransport(ZenohOptions options, const client::KeySpace & keys, client::Logger logger = {});
  ~ZenohTransport() override;

  std::optional<protocol::Bytes> query(
    const client::Target & target, const protocol::Bytes & payload, client::Duration timeout,
    const client::WaitHook * hook) override;
  void send(
    const client::Target & target, const protocol::Bytes & payload,
    client::Duration timeout) override;
  client::HostWatcher & hosts() override {return *watcher_;}

  // Where the session connects, for messages ("tcp/localhost:7447", "config file x.json5").
  const std::string & where() const noexcept {return where_;}

private:
  struct Link;  // the session and the liveliness subscriber

  // A link on `session`: its liveliness subscriber feeding watcher_.
  std::unique_ptr<Link> link_on(std::shared_ptr<zenoh::Session> session) const;
  bool try_open(bool quiet);
  // zenoh-pico: moves to a new session in place of one connected to nothing (or to the one
  // another plugin of this server opened in its place).
  // `why`: what is wrong with it, for the log ("" when another plugin reopened it).
  bool try_reopen(const std::shared_ptr<zenoh::Session> & stranded, const std::string & why);
  // The background thread: opens the session until it is open; on zenoh-pico, then watches it.
  void keep_linked();
  std::shared_ptr<zenoh::Session> session() const;

  ZenohOptions options_;
  std::string hosts_key_;
  client::Logger logger_;
  std::string where_;
  // Shared with the liveliness callback, which may outlive a destructor's undeclare by a call.
  std::shared_ptr<client::HostWatcher> watcher_;

  mutable std::mutex mutex_;
  std::condition_variable stop_cv_;
  bool stopping_{false};
  std::unique_ptr<Link> link_;
  std::thread keeper_;
};

}  // namespace nav2_pyif_bridge
