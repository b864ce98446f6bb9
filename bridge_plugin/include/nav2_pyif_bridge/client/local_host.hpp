// The plugin's own planner host: with `python_module` + `python_delegates` (or
// `python_planner`) and no host of its own, the plugin starts a `planner-host` child process
// serving that planner on a loopback endpoint, connects to it, and restarts it (with a
// back-off) when it exits. POSIX only; needs neither Nav2 nor Zenoh.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
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

// planner-host's argument vector for the plugin's python_* and planner_host_* parameters,
// serving `key`, listening on `listen_endpoint`. The host validates what they name.
std::vector<std::string> local_host_arguments(
  const BridgeParameters & spec, const std::string & key, const std::string & listen_endpoint);

// Runs a program and restarts it whenever it exits, until stop(). The child gets its own
// process group, PYTHONUNBUFFERED=1, and SIGTERM when the supervising thread dies (Linux), so
// a crashed Nav2 leaves no planner host behind.
class ProcessSupervisor
{
public:
  struct Options
  {
    std::vector<std::string> argv;  // argv[0]: the program, searched on $PATH (execvp)
    Duration restart_delay{std::chrono::seconds(1)};       // first back-off ...
    Duration max_restart_delay{std::chrono::seconds(30)};  // ... doubling up to this
    Duration stable_after{std::chrono::seconds(10)};  // a run this long resets the back-off
    Duration stop_grace{std::chrono::seconds(5)};     // SIGTERM, then SIGKILL after this
  };

  explicit ProcessSupervisor(Options options, Logger logger = {});
  ~ProcessSupervisor();
  ProcessSupervisor(const ProcessSupervisor &) = delete;
  ProcessSupervisor & operator=(const ProcessSupervisor &) = delete;

  // Start the first process (returns once it runs). Throws std::runtime_error when the
  // program is not found or cannot be started.
  void start();
  // Stop supervising: SIGTERM to the process, SIGKILL to its group after stop_grace. Idempotent.
  void stop();

  pid_t pid() const;          // 0 when no process runs
  unsigned starts() const;    // processes started so far
  std::string last_exit() const;  // "exited with status 3", "killed by signal 9 (SIGKILL)"
  // Block until `starts() >= n` or `timeout`; for tests and for waiting on a restart.
  bool wait_for_starts(unsigned n, Duration timeout) const;

private:
  void supervise();
  std::string spawn();  // "" once the process runs, else why not; mutex_ not held

  Options options_;
  Logger logger_;
  std::vector<std::string> environment_;

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  bool stopping_{false};
  pid_t pid_{0};
  unsigned starts_{0};
  std::string last_exit_;
  std::thread thread_;
};

// A planner host started for one plugin: picks a loopback port and a key, starts planner-host
// under a ProcessSupervisor. The plugin connects to endpoint() and uses key().
class LocalHost
{
public:
  // Throws std::runtime_error (planner-host not found, ...).
  LocalHost(
    const BridgeParameters & spec, std::string key, Logger logger = {},
    ProcessSupervisor::Options supervision = {});

  const std::string & key() const noexcept {return key_;}
  const std::string & endpoint() const noexcept {return endpoint_;}  // tcp/127.0.0.1:<port>
  ProcessSupervisor & process() noexcept {return *process_;}

private:
  std::string key_;
  std::string endpoint_;
  std::unique_ptr<ProcessSupervisor> process_;
};

}  // namespace nav2_pyif_bridge::client
