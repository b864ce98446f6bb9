// The plugin's own planner host: with `python_module` + `python_delegates` (or
// `python_planner`) and no host of its own, the plugin starts a `planner-host --respawn` child
// process serving that planner on a loopback endpoint and connects to it; that keeper restarts
// the host (with a back-off) when it exits. POSIX only; needs neither Nav2 nor Zenoh.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "nav2_pyif_bridge/client/clock.hpp"
#include "nav2_pyif_bridge/client/log.hpp"
#include "nav2_pyif_bridge/client/bridge_parameters.hpp"

namespace nav2_pyif_bridge::client
{

// A TCP port on 127.0.0.1 that was free a moment ago (bound to port 0, then released).
// Throws std::system_error.
std::uint16_t pick_free_tcp_port();

// The key a local host serves for a plugin: nav2_pyif/local/<node>/<plugin>, with characters
// a key chunk cannot hold replaced by '_'.
std::string local_host_key(std::string_view node, std::string_view plugin);

// planner-host's argument vector (with --respawn, and this process as the keeper's parent) for
// the plugin's python_* and planner_host_* parameters, serving `key`, listening on
// `listen_endpoint`. The host validates what they name.
std::vector<std::string> local_host_arguments(
  const BridgeParameters & spec, const std::string & key, const std::string & listen_endpoint);

// A planner host started for one plugin: picks a loopback port and runs
// local_host_arguments() in a process group of its own. The plugin connects to endpoint() and
// uses key().
class LocalHost
{
public:
  // Throws std::runtime_error: "cannot start '<planner-host>': <why>", ...
  LocalHost(
    const BridgeParameters & spec, std::string key, Logger logger = {},
    Duration stop_grace = std::chrono::seconds(5));
  ~LocalHost() {stop();}
  LocalHost(const LocalHost &) = delete;
  LocalHost & operator=(const LocalHost &) = delete;

  const std::string & key() const noexcept {return key_;}
  const std::string & endpoint() const noexcept {return endpoint_;}  // tcp/127.0.0.1:<port>
  pid_t pid() const noexcept {return pid_;}  // 0 once stopped

  // SIGTERM to the child, SIGKILL to its process group after stop_grace; reaps it, then
  // SIGKILLs what is left of the group (the host's workers). Returns the child's wait status
  // (waitpid), -1 when already stopped.
  int stop();

private:
  std::string key_;
  std::string endpoint_;
  Logger logger_;
  Duration stop_grace_;
  pid_t pid_{0};
};

}  // namespace nav2_pyif_bridge::client
