// Test doubles for the client units: a fake clock, a fake planner host behind the Transport
// interface (it decodes every request with the real codec and follows the host rules of
// PROTOCOL.md section 4, answering like tests/fixtures/echo_planners.py), and a costmap grid.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/client/clock.hpp"
#include "nav2_pyif_bridge/client/costmap_version.hpp"
#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/client/host_watcher.hpp"
#include "nav2_pyif_bridge/client/log.hpp"
#include "nav2_pyif_bridge/client/transport.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"

namespace nav2_pyif_bridge::client::test
{

using namespace std::chrono_literals;

// Time moves only when advanced: by the test, by a fake host doing work, or by a wait.
class FakeClock : public Clock
{
public:
  TimePoint now() const override;
  // A wait returns at the next scheduled event or at its timeout, whichever is first.
  void wait_for(
    std::condition_variable & cv, std::unique_lock<std::mutex> & lock,
    Duration timeout) override;

  // Move time forward, running each event scheduled up to the new time, in order.
  void advance(Duration duration);
  // Run `event` when the clock reaches `elapsed()` == at.
  void at(Duration at, std::function<void()> event);
  Duration elapsed() const;

private:
  std::optional<Duration> next_event() const;

  mutable std::mutex mutex_;
  Duration now_{0};
  std::multimap<Duration, std::function<void()>> events_;
};

// A costmap as a plain grid; read() goes through the real CostmapVersion.
class GridCostmap : public CostmapSource
{
public:
  GridCostmap(std::uint32_t size_x = 40, std::uint32_t size_y = 40, double resolution = 0.05);
  CostmapRead read(std::optional<std::uint64_t> known) override;

  std::string frame_id{"odom"};
  std::uint32_t size_x;
  std::uint32_t size_y;
  double resolution;
  double origin_x{0.0};
  double origin_y{0.0};
  std::vector<std::uint8_t> data;
  std::vector<double> footprint{0.2, 0.1, 0.2, -0.1, -0.2, -0.1, -0.2, 0.1};
  double robot_radius{0.0};
  int reads{0};

private:
  CostmapVersion version_;
};

// The planner hosts serving one key, as the plugin sees them through Transport: a primary
// host (kill / start / restart) and, for the replica tests, more hosts by id.
class FakeHost : public Transport
{
public:
  explicit FakeHost(FakeClock & clock, bool alive = true);

  // --- Transport ---
  std::optional<protocol::Bytes> query(
    const Target & target, const protocol::Bytes & payload, Duration timeout,
    const WaitHook * hook) override;
  void send(const Target & target, const protocol::Bytes & payload, Duration timeout) override;
  HostWatcher & hosts() override {return watcher_;}

  // --- the primary host's process ---
  void kill();     // SIGKILL: its token goes, its sessions are lost
  void start();    // a new process: a new host id, no sessions, its token appears
  void restart() {kill(); start();}
  const std::string & host_id() const {return primary_;}

  // --- replicas ---
  void add_replica(const std::string & id);
  void kill_replica(const std::string & id);           // token gone, sessions lost
  void freeze_replica(const std::string & id, bool frozen = true);  // alive, never answers
  bool has_session(const std::string & host, const std::string & sid) const;

  // --- what the hosts received ---
  struct Received
  {
    std::string key;
    std::string host;  // the Target's host ("" for any)
    protocol::Request request;
    std::size_t bytes{0};
    bool answered{false};  // false: nobody answered before the plugin's timeout
    std::string answered_by;
    Duration timeout{};  // how long the plugin waited for the reply
  };
  std::vector<Received> received;
  std::vector<std::string> carried_ops;  // op names of the requests other queries carried
  std::vector<std::string> ops() const;  // op names of `received`, in order
  std::vector<std::string> ops_since(std::size_t index) const;
  const protocol::Request & last() const {return received.back().request;}
  bool last_had_costmap() const;

  // --- faults and timing (whichever host answers) ---
  Duration call_time{0};                     // how long each call takes
  std::optional<Duration> next_call_time;    // ... or the next one only
  int seq_offset_once{0};                    // the next reply answers another seq
  std::optional<protocol::Error> error_once; // the next call fails with this
  bool always_session_unknown{false};        // every non-configure call: SessionUnknown
  bool nan_once{false};                      // the next command has vx = NaN (host not checking)
  std::optional<protocol::Bytes> raw_reply_once;  // the next reply is these bytes
  bool transport_error_once{false};          // the next query throws (a broken Zenoh session)
  // The answering host dies this far into the next call: its token goes, its sessions are
  // lost, and the query ends at once with no reply (what Zenoh does when a queryable goes).
  std::optional<Duration> dies_during_next_call;
  bool making_progress{true};                // what progress checks answer
  double reached_x{1e9};                     // goal checks answer reached from this pose x on

  // What one session knows, echoed by compute_velocity_commands.
  struct Session
  {
    std::uint64_t epoch{0};
    protocol::Params params;
    double plan_size{-1.0};
    double speed_limit{-1.0};
    std::uint64_t costmap_version{0};
    double calls{0.0};
    bool active{false};
    // a behaviour's action: on_run's count, start x and distance (|target_x|)
    std::int64_t runs{0};
    double start_x{0.0};
    double distance{0.0};
  };

private:
  struct Replica
  {
    bool alive{true};
    bool frozen{false};
    std::map<std::string, Session> sessions;
  };
  // Who answers a query for `host`: that replica, or with no host the smallest alive one.
  Replica * answering(const std::string & host, std::string * id);
  protocol::Reply handle(
    Replica & replica, const std::string & id, const protocol::Request & request,
    Duration elapsed);
  protocol::Reply error(
    const std::string & id, const protocol::Request & request, std::string type,
    std::string message);
  // The requests carried in another's query (PROTOCOL.md section 15), each answered as on
  // its own, in order, as far as Nav2 would go (the host's carried.py).
  std::optional<std::vector<protocol::CarriedCall>> carried(
    Replica & replica, const std::string & id,
    const std::optional<std::vector<protocol::CarriedCall>> & carry);

  FakeClock & clock_;
  HostWatcher watcher_;
  std::map<std::string, Replica> replicas_;
  std::string primary_;
  int generation_{0};
  std::uint64_t running_seq_{0};  // create_plan being computed
  bool cancel_requested_{false};
};

// Collects what a unit logs.
struct LogSink
{
  std::vector<std::pair<LogLevel, std::string>> lines;
  Logger logger()
  {
    return [this](LogLevel level, const std::string & text) {lines.emplace_back(level, text);};
  }
  bool contains(const std::string & text) const;
};

// The CallError `call` throws; fails the test (and returns a Local error) when it throws none.
template<class Call>
CallError error_of(Call && call)
{
  try {
    call();
  } catch (const CallError & e) {
    return e;
  }
  ADD_FAILURE() << "no CallError thrown";
  return CallError(ErrorKind::ControllerException, Cause::Local, "none");
}

// A straight n-pose path from (0, 0) to (x, y) in frame "odom".
protocol::Path straight_path(std::size_t n, double x, double y);
protocol::PoseStamped pose_at(double x, double y, const std::string & frame = "odom");
// A create_plan request from `start` to `goal`.
protocol::CreatePlanRequest plan_request(
  const protocol::PoseStamped & start, const protocol::PoseStamped & goal);

}  // namespace nav2_pyif_bridge::client::test
