// One plugin instance's session with the planner host: sid, epoch and seq, and the call
// procedure of PROTOCOL.md section 4 ("Plugin rules"), exactly as the reference client
// (python/nav2_pyif/client/plugin_client.py) does it:
//   1. no host alive under P/host/*: fail at once with the host-failure exception, send nothing;
//   2. no reply within the op's timeout: the host-failure exception (NoValidControl, ...);
//   3. SessionUnknown (the host restarted, or another replica answered): epoch + 1, configure
//      (current parameters, full costmap), activate if active, re-send the state schema.py's
//      RESTORED names (plan, speed limit, ...), then retry the call once; a second
//      SessionUnknown fails it;
//   4. the costmap travels only when its version differs from the one this session last
//      delivered (delivered = sent in a request that got an ok reply; configure forgets it);
//   5. a reply of another seq, or one that does not decode, fails the call (generic);
//   6. other error replies throw the nav2_core-named exception (error_mapping.hpp);
//   7. replicas (PROTOCOL.md section 1): the session pins the smallest alive host id and
//      addresses every query to it (Target::host); when the pinned host's token is gone, or
//      a call gets no reply in time, a bad reply or Unavailable while another host is alive,
//      it pins another one and retries the call once there (whose SessionUnknown re-sends
//      the state), so a replica's death fails no call.
// Every failure is a CallError. Thread-safe: each public call holds the session's lock (Nav2
// calls from its action thread, parameter changes come from the executor's thread).
//
// Two additions for a plugin living inside Nav2 (the reference client has no need of them):
// - defer_configure(): Nav2 configures its plugins at bring-up, maybe before any host runs.
//   The plugin then marks the session configured without a host; the first call that needs
//   the host establishes it as rule 3 does (configure, activate if active, state), and
//   activate/deactivate/cleanup/set_parameters before that only update the local state.
// - activate/deactivate with no host (none alive, or no reply in time) do not fail: Nav2's
//   lifecycle goes on, and the next call re-establishes the session in the new state.
// - a failed re-establishment leaves the session configured and not established, so the
//   next call tries again (the reference client would refuse every later call).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "nav2_pyif_bridge/client/bridge_parameters.hpp"
#include "nav2_pyif_bridge/client/costmap_version.hpp"
#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/client/keys.hpp"
#include "nav2_pyif_bridge/client/log.hpp"
#include "nav2_pyif_bridge/client/transport.hpp"
#include "nav2_pyif_bridge/protocol/codec.hpp"

namespace nav2_pyif_bridge::client
{

struct SessionConfig
{
  PluginKind kind{PluginKind::Controller};
  std::string key_prefix;        // P (validated: std::invalid_argument)
  std::string name;              // plugin name in Nav2, e.g. FollowPath
  std::string node;              // the Nav2 server node, e.g. controller_server
  protocol::Params params;       // forwarded in configure (prefix stripped)
  protocol::Params nav2_params;  // configure's nav2_params (controller_frequency, inflation)
  std::string global_frame;      // the costmap's global frame
  std::string robot_base_frame{"base_link"};
  Timeouts timeouts;
  std::string session_id;        // "": a new random one (the session transcripts fix it)
};

class CarriedCycle;

// A request prepared to travel inside another plugin's query (PROTOCOL.md section 15): a
// call of the control cycle carries those that follow it.
struct Carried
{
  protocol::Request request;
  protocol::Bytes payload;                      // the encoded request
  std::optional<std::uint64_t> costmap_version;  // the costmap it was prepared with
  bool costmap_sent{false};
};

class PluginSession
{
public:
  // A session of the `kind` plugin type (config.kind is set to it). `transport` and `costmap`
  // must outlive the session.
  PluginSession(
    PluginKind kind, SessionConfig config, Transport & transport, CostmapSource & costmap,
    Logger logger = {});
  // Leaves its carried cycle (the cycle then prepares nothing more for it).
  virtual ~PluginSession();
  PluginSession(const PluginSession &) = delete;
  PluginSession & operator=(const PluginSession &) = delete;

  // Start a session (epoch + 1, full costmap); returns the parameters the planner declared.
  // Those the session did not have join its parameters (sent again in a later configure).
  // Given parameters the planner ignores (the reply's `undeclared`: a misspelt name in the
  // params YAML) are logged as a warning, naming each with the host's reason.
  protocol::Params configure();
  // Configured without a host yet: the first call establishes the session (see above).
  void defer_configure();
  void activate();
  void deactivate();
  // Ends the session; configured and active are false afterwards even when the call failed.
  void cleanup();
  // Send changed parameters; returns the rejected ones (name -> reason). The accepted ones
  // join the parameters re-sent by a later configure. Before the session is established,
  // the changes are only kept for configure (nothing rejects them).
  protocol::StringMap set_parameters(const protocol::Params & changes);

  // The carried cycle of the controller_server this plugin is in (carried_cycle.hpp);
  // nullptr until joined.
  void join(std::shared_ptr<CarriedCycle> cycle);
  CarriedCycle * cycle() const noexcept {return cycle_.get();}

  // Block until a host is alive (the transport's liveliness watch); false on timeout.
  bool wait_for_host(Duration timeout);

  // --- state, for the plugins' logs and the tests ---
  const KeySpace & keys() const noexcept {return keys_;}
  PluginKind kind() const noexcept {return config_.kind;}
  const std::string & sid() const noexcept {return sid_;}
  std::uint64_t epoch() const;
  std::uint64_t last_seq() const;
  bool configured() const;
  bool established() const;
  bool active() const;
  std::uint64_t resyncs() const;              // re-establishments after SessionUnknown
  std::string last_host() const;              // the host of the last reply
  std::string served() const;                 // the configure reply's planner; "" if unsaid
  // The debug outputs the served planner may return (name -> ROS type), from configure.
  protocol::StringMap debug_outputs() const;
  std::string pinned_host() const;            // the replica queries go to; "" before the first
  std::uint64_t failovers() const;            // times another replica was pinned
  std::optional<std::uint64_t> delivered_costmap() const;
  protocol::Params params() const;
  Timeouts timeouts() const;
  void set_timeouts(const Timeouts & timeouts);

protected:
  struct CallOptions
  {
    bool allow_resync{true};
    bool allow_failover{true};
    std::optional<Duration> timeout;  // instead of the op's (Timeouts::for_op)
    // Runs about every 5 ms while waiting for the reply, with the request's seq.
    std::function<void(std::uint64_t)> while_waiting;
  };

  // A request for another plugin's query to carry, numbered and with the costmap as call()
  // would send them; std::nullopt when this session cannot send one now (not established:
  // its call on its own establishes it). The caller holds mutex().
  std::optional<Carried> prepare(protocol::RequestBody body);
  // The body of the reply to a carried request, as call() would return it; std::nullopt when
  // the call must go on its own: it did not run, or its host does not serve this key or know
  // this session (Unavailable, SessionUnknown: the call on its own re-establishes it). Other
  // errors throw as call() does. The caller holds mutex().
  std::optional<protocol::ReplyBody> settle(
    const Carried & carried, const std::optional<protocol::Bytes> & reply);
  // The body of the reply to a carried request for Nav2's call `body`, when that call is the
  // prepared one: its request encodes to the same bytes (the prepared seq, and the costmap
  // as call() would attach it) and nothing was sent on this session since it was prepared;
  // then as settle(). Else std::nullopt: the call goes on its own. mutex() held.
  std::optional<protocol::ReplyBody> take(
    Carried carried, const std::optional<protocol::Bytes> & reply, protocol::RequestBody body);

  // One call, following rules 1-6. The caller holds mutex().
  protocol::ReplyBody call(const protocol::RequestBody & body, const CallOptions & options);
  template<class ReplyT>
  ReplyT call_for(const protocol::RequestBody & body, const CallOptions & options = {})
  {
    return std::get<ReplyT>(call(body, options));
  }

  // The request that tells a new session on the host `op`'s part of what the planner was
  // told since configure, for each op schema.py's RESTORED lists for this plugin type, in
  // its order (the plan, the speed limit, ...); std::nullopt: nothing to re-send. mutex() held.
  virtual std::optional<protocol::RequestBody> restored(protocol::Op /*op*/)
  {
    return std::nullopt;
  }
  // Forget that state (cleanup ends the session); mutex() held.
  virtual void forget_state() {}

  std::recursive_mutex & mutex() const noexcept {return mutex_;}
  Transport & transport() noexcept {return transport_;}
  const Logger & logger() const noexcept {return logger_;}
  std::uint64_t next_seq() noexcept {return ++seq_;}
  // Where a query for `key` goes: the pinned replica.
  Target target(std::string key) const {return Target{std::move(key), pinned_host_};}
  [[noreturn]] void fail(ErrorKind kind, Cause cause, const std::string & message) const;

private:
  protocol::Params configure_locked();
  void establish();
  void unreachable_transition(const CallError & error, bool active);
  void reestablish(const std::string & host);
  void pin_host();
  bool fail_over(const std::optional<std::string> & avoid);
  protocol::Reply exchange(const protocol::Request & request, const CallOptions & options);
  // The decoded reply to `request`, else BadReply ("bad <what> to <op>: ...", or its seq).
  protocol::Reply checked_reply(
    const protocol::Bytes & answer, const protocol::Request & request,
    const std::string & what) const;
  // The costmap read for a request, and whether it was attached (delivered once answered ok).
  struct CostmapAttached
  {
    std::optional<std::uint64_t> version;
    bool sent{false};
  };
  // Attaches the costmap to `request` as schema.py's COSTMAP_SENT says its op takes it.
  CostmapAttached attach_costmap(protocol::Request & request);

  SessionConfig config_;
  KeySpace keys_;
  Transport & transport_;
  CostmapSource & costmap_;
  Logger logger_;
  std::string sid_;

  mutable std::recursive_mutex mutex_;
  std::uint64_t epoch_{0};
  std::uint64_t seq_{0};
  bool configured_{false};
  bool established_{false};
  bool active_{false};
  std::uint64_t resyncs_{0};
  std::string last_host_;
  std::string served_;
  protocol::StringMap debug_outputs_;
  std::string pinned_host_;
  std::uint64_t failovers_{0};
  std::optional<std::uint64_t> delivered_costmap_;
  std::shared_ptr<CarriedCycle> cycle_;
};

// The base of the sessions of one plugin type: ControllerSession, PlannerSession,
// SmootherSession, GoalCheckerSession, ProgressCheckerSession.
template<PluginKind Kind>
class KindSession : public PluginSession
{
public:
  static constexpr PluginKind kKind = Kind;

  // config.kind is set to Kind.
  KindSession(
    SessionConfig config, Transport & transport, CostmapSource & costmap, Logger logger = {})
  : PluginSession(Kind, std::move(config), transport, costmap, std::move(logger)) {}
};

// The same pose message, header included: whether Nav2's call is the one a carried request
// was prepared for.
inline bool same_pose(const protocol::PoseStamped & a, const protocol::PoseStamped & b) noexcept
{
  return a.frame_id == b.frame_id && a.stamp_ns == b.stamp_ns && a.pose == b.pose;
}

// A random UUID4 as 32 lowercase hex digits (Python's uuid.uuid4().hex).
std::string new_session_id();

}  // namespace nav2_pyif_bridge::client
