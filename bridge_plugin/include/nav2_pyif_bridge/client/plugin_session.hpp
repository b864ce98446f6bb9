// One plugin instance's session with the planner host: sid, epoch and seq, and the call
// procedure as PROTOCOL.md states it and the reference client (python/nav2_pyif/client/
// plugin_client.py) does it: the plugin rules of section 4 (fail fast without a host,
// SessionUnknown -> re-establish and retry once), the replicas of section 1 (pin one, fail
// over), the costmap of section 5 (only when changed), the timeouts of section 8, the
// reply checks and nav2_core exceptions of section 7. Every failure is a CallError.
// Thread-safe: each public call holds the session's lock (Nav2 calls from its action thread,
// parameter changes come from the executor's thread).
//
// Additions for a plugin living inside Nav2 (the reference client has no need of them):
// - defer_configure(): Nav2 configures its plugins at bring-up, maybe before any host runs.
//   The plugin then marks the session configured without a host; the first call that needs
//   the host establishes it as a re-establishment does, and activate/deactivate/cleanup/
//   set_parameters before that only update the local state.
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
#include <vector>

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

// The costmap read for a request, and whether it was attached (delivered once answered ok).
struct CostmapAttached
{
  std::optional<std::uint64_t> version;
  bool sent{false};
};

// A request prepared to travel inside another plugin's query (PROTOCOL.md section 15): a
// call of the control cycle carries those that follow it.
struct Carried
{
  protocol::Request request;
  protocol::Bytes payload;  // the encoded request
  CostmapAttached costmap;  // the costmap it was prepared with
};

// `body` carrying `carry` (the encoded requests of the calls that follow it in the control
// cycle), when there is any: an empty list is left out of the request.
template<class Request>
Request carrying(Request body, std::vector<protocol::CarriedCall> carry)
{
  if (!carry.empty()) {
    body.carry = std::move(carry);
  }
  return body;
}

// What a session is now, for the plugins' logs and the tests.
struct SessionState
{
  std::uint64_t epoch{0};
  std::uint64_t last_seq{0};
  bool configured{false};
  bool established{false};
  bool active{false};
  std::uint64_t resyncs{0};                      // re-establishments after SessionUnknown
  std::string last_host;                         // the host of the last reply
  std::string served;                            // the configure reply's planner; "" if unsaid
  protocol::StringMap debug_outputs;             // the served planner's (name -> ROS type)
  std::string pinned_host;                       // the replica queries go to
  std::uint64_t failovers{0};                    // times another replica was pinned
  std::optional<std::uint64_t> delivered_costmap;
};

struct CallOptions
{
  bool allow_resync{true};
  bool allow_failover{true};
  std::optional<Duration> timeout;  // instead of the op's (Timeouts::for_op)
  // Runs about every 5 ms while waiting for the reply, with the request's seq.
  std::function<void(std::uint64_t)> while_waiting;
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

  // One call of `body`'s op, by PROTOCOL.md section 4's plugin rules; its reply's body. Every
  // failure is a CallError.
  template<class Request>
  protocol::ReplyOf<Request> call(const Request & body, const CallOptions & options = {})
  {
    std::lock_guard<std::recursive_mutex> lock(mutex_);
    return std::get<protocol::ReplyOf<Request>>(call_body(body, options));
  }

  // A request for another plugin's query to carry (PROTOCOL.md section 15), numbered and
  // with the costmap as call() would send them; std::nullopt when this session cannot send
  // one now (not established: its call on its own establishes it).
  std::optional<Carried> prepare(protocol::RequestBody body);
  // The reply to a carried request for Nav2's call `body`, when that call is the prepared
  // one: its request encodes to the same bytes (the prepared seq, and the costmap as call()
  // would attach it) and nothing was sent on this session since it was prepared. Else, or
  // when the carried call did not run, or its host does not serve this key or know this
  // session (Unavailable, SessionUnknown), std::nullopt: the call goes on its own. Other
  // errors throw as call() does.
  template<class Request>
  std::optional<protocol::ReplyOf<Request>> take(
    Carried carried, const std::optional<protocol::Bytes> & reply, Request body)
  {
    std::lock_guard<std::recursive_mutex> lock(mutex_);
    auto out = take_body(std::move(carried), reply, std::move(body));
    if (!out) {
      return std::nullopt;
    }
    return std::get<protocol::ReplyOf<Request>>(std::move(*out));
  }

  // The carried cycle of the controller_server this plugin is in (carried_cycle.hpp);
  // nullptr until joined.
  void join(std::shared_ptr<CarriedCycle> cycle);
  CarriedCycle * cycle() const noexcept {return cycle_.get();}

  // Block until a host is alive (the transport's liveliness watch); false on timeout.
  bool wait_for_host(Duration timeout);

  const KeySpace & keys() const noexcept {return keys_;}
  PluginKind kind() const noexcept {return config_.kind;}
  const std::string & sid() const noexcept {return sid_;}
  SessionState state() const;
  // The two reads of the control cycle (state() copies every string): the seq last sent, and
  // the debug outputs the served planner declares.
  std::uint64_t last_seq() const
  {
    std::lock_guard<std::recursive_mutex> lock(mutex_);
    return state_.last_seq;
  }
  protocol::StringMap debug_outputs() const
  {
    std::lock_guard<std::recursive_mutex> lock(mutex_);
    return state_.debug_outputs;
  }
  protocol::Params params() const;
  Timeouts timeouts() const;
  void set_timeouts(const Timeouts & timeouts);

protected:
  // The request that tells a new session on the host `op`'s part of what the planner was
  // told since configure, for each op schema.py's RESTORED lists for this plugin type, in
  // its order (the plan, the speed limit, ...); std::nullopt: nothing to re-send. mutex() held.
  virtual std::optional<protocol::RequestBody> restored(protocol::Op /*op*/)
  {
    return std::nullopt;
  }
  // Forget that state (cleanup ends the session); mutex() held.
  virtual void forget_state() {}

  // One call (call()'s procedure), the caller holding mutex().
  protocol::ReplyBody call_body(const protocol::RequestBody & body, const CallOptions & options);
  // The session's state, the caller holding mutex().
  const SessionState & current() const noexcept {return state_;}
  std::recursive_mutex & mutex() const noexcept {return mutex_;}
  Transport & transport() noexcept {return transport_;}
  const Logger & logger() const noexcept {return logger_;}
  std::uint64_t next_seq() noexcept {return ++state_.last_seq;}
  // Where a query for `key` goes: the pinned replica.
  Target target(std::string key) const {return Target{std::move(key), state_.pinned_host};}
  [[noreturn]] void fail(ErrorKind kind, Cause cause, const std::string & message) const;

private:
  protocol::Params configure_locked();
  void establish();
  // activate (true) or deactivate; with no host, only the state the next call sends.
  void transition(bool active);
  void reestablish(const std::string & host);
  void pin_host();
  // Pins another alive replica than the pinned one and `avoid`; false when there is none.
  bool fail_over(const std::string & avoid);
  std::optional<protocol::ReplyBody> take_body(
    Carried carried, const std::optional<protocol::Bytes> & reply, protocol::RequestBody body);
  // The body of the reply to a carried request, as call() would return it (take()).
  std::optional<protocol::ReplyBody> settle(
    const Carried & carried, const std::optional<protocol::Bytes> & reply);
  protocol::Reply exchange(const protocol::Request & request, const CallOptions & options);
  // The decoded reply to `request`, else BadReply ("bad <what> to <op>: ...", or its seq).
  protocol::Reply checked_reply(
    const protocol::Bytes & answer, const protocol::Request & request,
    const std::string & what) const;
  // How long a call of `body` waits for its reply and, for a plan-class op, for a host: its
  // timeout class's (schema.py OP_TIMEOUT), a smooth's max_time and SMOOTH_GRACE_S if longer.
  Duration timeout_of(const protocol::RequestBody & body) const;
  // A request of this session's sid and epoch (seq 0) with the costmap attached as schema.py's
  // COSTMAP_SENT says `body`'s op takes it.
  protocol::Request request_for(protocol::RequestBody body, CostmapAttached & costmap);
  // The body of an ok reply to a request of `body`, checked; the costmap it took delivered.
  protocol::ReplyBody accepted(
    protocol::Reply & reply, const protocol::RequestBody & body, const CostmapAttached & costmap);

  SessionConfig config_;
  KeySpace keys_;
  Transport & transport_;
  CostmapSource & costmap_;
  Logger logger_;
  std::string sid_;

  mutable std::recursive_mutex mutex_;
  SessionState state_;
  std::shared_ptr<CarriedCycle> cycle_;
};

// The base of the sessions of one plugin type: ControllerSession, PlannerSession,
// BehaviorSession, and the aliases below.
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

// The plugin types whose calls need nothing of their own: PluginSession's typed call, prepare
// and take serve them. None has state to re-send after a host restart.
using GoalCheckerSession = KindSession<PluginKind::GoalChecker>;
using ProgressCheckerSession = KindSession<PluginKind::ProgressChecker>;
using CostmapLayerSession = KindSession<PluginKind::CostmapLayer>;
using SmootherSession = KindSession<PluginKind::Smoother>;

// The same pose message, header included: whether Nav2's call is the one a carried request
// was prepared for.
inline bool same_pose(const protocol::PoseStamped & a, const protocol::PoseStamped & b) noexcept
{
  return a.frame_id == b.frame_id && a.stamp_ns == b.stamp_ns && a.pose == b.pose;
}

// A random UUID4 as 32 lowercase hex digits (Python's uuid.uuid4().hex).
std::string new_session_id();

}  // namespace nav2_pyif_bridge::client
