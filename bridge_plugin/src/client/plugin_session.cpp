#include "nav2_pyif_bridge/client/plugin_session.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/client/command_check.hpp"

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

namespace
{

template<class T, class = void>
struct HasCostmap : std::false_type {};
template<class T>
struct HasCostmap<T, std::void_t<decltype(std::declval<T &>().costmap)>> : std::true_type {};

// Sets the costmap field of a request that has one (schema.py COSTMAP_SENT says which ops'
// requests carry it, and when).
void set_costmap(proto::RequestBody & body, proto::Costmap costmap)
{
  std::visit(
    [&costmap](auto & request) {
      if constexpr (HasCostmap<std::decay_t<decltype(request)>>::value) {
        request.costmap = std::move(costmap);
      }
    }, body);
}

void move_costmap(proto::RequestBody & from, proto::RequestBody & to)
{
  std::visit(
    [&to](auto & request) {
      using Body = std::decay_t<decltype(request)>;
      if constexpr (HasCostmap<Body>::value) {
        if (auto * target = std::get_if<Body>(&to)) {
          target->costmap = std::move(request.costmap);
        }
      }
    }, from);
}

std::string milliseconds(Duration d)
{
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.0f", to_ms(d));
  return text.data();
}

// Whether a query with no reply ended before its timeout: Zenoh ends one early when the host
// it went to is gone. A query that ran out ends at about the timeout, a little before by
// Zenoh's clock: 5 % spare, as the Python client allows (no_reply_message).
bool ended_before(Duration waited, Duration timeout)
{
  return waited < timeout * 0.95;
}

}  // namespace

std::string new_session_id()
{
  std::random_device device;
  std::uniform_int_distribution<std::uint64_t> any;
  const std::uint64_t high = (any(device) & ~std::uint64_t{0xf000}) | 0x4000;  // version 4
  const std::uint64_t low = (any(device) >> 2) | (std::uint64_t{1} << 63);  // RFC 4122 variant
  std::array<char, 33> text{};
  std::snprintf(
    text.data(), text.size(), "%016llx%016llx", static_cast<unsigned long long>(high),
    static_cast<unsigned long long>(low));
  return text.data();
}

PluginSession::PluginSession(
  PluginKind kind, SessionConfig config, Transport & transport, CostmapSource & costmap,
  Logger logger)
: config_(std::move(config)), keys_(config_.key_prefix), transport_(transport),
  costmap_(costmap), logger_(std::move(logger)),
  sid_(config_.session_id.empty() ? new_session_id() : config_.session_id)
{
  config_.kind = kind;
}

// --- lifecycle ------------------------------------------------------------------------------

proto::Params PluginSession::configure()
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  return configure_locked();
}

proto::Params PluginSession::configure_locked()
{
  ++state_.epoch;
  state_.delivered_costmap.reset();
  state_.established = false;
  proto::ConfigureRequest body;
  body.plugin_type = std::string(plugin_type_name(config_.kind));
  body.name = config_.name;
  body.node = config_.node;
  body.params = config_.params;
  body.global_frame = config_.global_frame;
  body.robot_base_frame = config_.robot_base_frame;
  if (!config_.nav2_params.empty()) {
    body.nav2_params = config_.nav2_params;
  }
  CallOptions options;
  options.allow_resync = false;
  auto reply = call(body, options);
  state_.configured = true;
  state_.established = true;
  state_.served = reply.planner.value_or("");
  state_.debug_outputs = reply.debug_outputs.value_or(proto::StringMap{});
  if (reply.undeclared && !reply.undeclared->empty()) {
    std::string names;
    std::string reasons;
    for (const auto & [name, reason] : *reply.undeclared) {
      names += (names.empty() ? "" : ", ") + name;
      reasons += (reasons.empty() ? "" : "; ") + reason;
    }
    // What the planner declares, once for all names (the host's reasons leave it out).
    std::vector<std::string> declared;
    for (const auto & [name, value] : reply.declared) {
      declared.push_back(name);
    }
    std::sort(declared.begin(), declared.end());
    std::string declares;
    for (const auto & name : declared) {
      declares += (declares.empty() ? "" : ", ") + name;
    }
    log(
      logger_, LogLevel::Warn,
      keys_.prefix() + ": the planner ignores parameter(s) " + names + ": " + reasons +
      "; it declares: " + (declares.empty() ? std::string("none") : declares));
  }
  for (const auto & [name, value] : reply.declared) {
    if (config_.params.find(name) == nullptr) {
      config_.params.set(name, value);
    }
  }
  return std::move(reply.declared);
}

void PluginSession::defer_configure()
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  state_.configured = true;
  state_.established = false;
}

void PluginSession::activate() {transition(true);}
void PluginSession::deactivate() {transition(false);}

void PluginSession::transition(bool active)
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  try {
    if (state_.configured && !state_.established) {
      state_.active = active;  // sent when the session is established
      if (active && transport_.hosts_alive()) {
        establish();
      }
      return;
    }
    if (active) {
      call(proto::ActivateRequest{});
    } else {
      call(proto::DeactivateRequest{});
    }
    state_.active = active;
  } catch (const CallError & error) {
    if (!error.unreachable()) {
      throw;
    }
    state_.active = active;
    state_.established = false;  // the next call re-establishes, in this state
    log(
      logger_, LogLevel::Warn,
      keys_.prefix() + ": " + error.what() + "; the session is re-established (" +
      (active ? "active" : "inactive") + ") by the next call");
  }
}

void PluginSession::cleanup()
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  // not configured: the call says so
  const bool send = !state_.configured || state_.established;
  struct Reset
  {
    PluginSession & session;
    ~Reset()
    {
      session.state_.configured = false;
      session.state_.established = false;
      session.state_.active = false;
      session.forget_state();
    }
  } reset{*this};
  if (send) {
    CallOptions options;
    options.allow_resync = false;
    call(proto::CleanupRequest{}, options);
  }
}

proto::StringMap PluginSession::set_parameters(const proto::Params & changes)
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  if (!state_.configured || !state_.established) {
    for (const auto & [name, value] : changes) {
      config_.params.set(name, value);
    }
    return {};
  }
  auto reply = call(proto::SetParametersRequest{changes});
  for (const auto & [name, value] : changes) {
    if (reply.rejected.find(name) == nullptr) {
      config_.params.set(name, value);
    }
  }
  return std::move(reply.rejected);
}

bool PluginSession::wait_for_host(Duration timeout)
{
  return transport_.wait_for_host(timeout);  // without the session's lock: calls may go on
}

// --- the call procedure ---------------------------------------------------------------------

proto::ReplyBody PluginSession::call_body(
  const proto::RequestBody & body, const CallOptions & options)
{
  const proto::Op op = proto::op_of(body);
  const std::string op_text(proto::op_name(op));
  if (op != proto::Op::Configure && !state_.configured) {
    fail(
      generic_error(config_.kind), Cause::NotConfigured,
      op_text + " before configure on " + keys_.prefix());
  }
  // A plan-class op (create_plan, smooth) runs in its server's own thread while the robot
  // follows its last path: without a host it waits, up to its timeout, for one to come back,
  // as it would for a slow planner, so that a host restart costs no recovery. The control
  // loop's and the lifecycle's ops fail at once.
  const bool plan_class = proto::timeout_class(op) == proto::TimeoutClass::Plan;
  const Duration timeout = options.timeout.value_or(timeout_of(body));
  const Clock & clock = transport_.hosts().clock();
  const TimePoint started = clock.now();
  if (!transport_.hosts_alive() && !(plan_class && transport_.wait_for_host(timeout))) {
    fail(
      host_failure_error(config_.kind), Cause::NoHost,
      "no planner host is alive on " + keys_.prefix() + " (start one: planner-host --key " +
      keys_.prefix() + " ...); " + op_text + " not sent");
  }
  pin_host();
  if (op != proto::Op::Configure && !state_.established) {
    establish();  // deferred configure, or a re-establishment that failed before
  }

  CostmapAttached costmap;
  proto::Request request = request_for(body, costmap);
  request.seq = next_seq();

  // After a fail-over: once, on the new replica, whose SessionUnknown re-sends the state.
  CallOptions retry = options;
  retry.allow_failover = false;
  retry.allow_resync = true;
  proto::Reply reply;
  const TimePoint sent = clock.now();
  try {
    reply = exchange(request, options);
  } catch (const CallError & error) {
    // No reply in time (the pinned replica died before its token went, or hangs), or a bad
    // one: another alive replica gets the call instead.
    const bool exchange_failed = error.cause() == Cause::TimedOut ||
      error.cause() == Cause::BadReply;
    if (exchange_failed && options.allow_failover && fail_over(state_.pinned_host)) {
      return call_body(body, retry);
    }
    // The only host died with a plan-class call in it: its query ended early with no reply,
    // or failed at once where the host was the Zenoh session's only link (its liveliness
    // token may go a moment later). As before a call, wait within what is left of the op's
    // timeout for that host to be gone and another to be alive (its restart), and send the
    // call once more, so that a host restart mid-plan costs no recovery either.
    const std::string gone = state_.pinned_host;
    const bool ended_early = ended_before(clock.now() - sent, timeout);
    const bool no_reply = error.cause() == Cause::TimedOut || error.cause() == Cause::Transport;
    if (no_reply && options.allow_failover && plan_class &&
      (ended_early || transport_.hosts().alive().count(gone) == 0))
    {
      const Duration left = timeout - (clock.now() - started);
      const auto restarted = [&gone](const HostWatcher::Hosts & hosts) {
          return hosts.count(gone) == 0 && !hosts.empty();
        };
      if (left > Duration::zero() && transport_.hosts().wait_until(restarted, left)) {
        log(
          logger_, LogLevel::Warn,
          keys_.prefix() + ": host " + gone + " went away during " + op_text +
          "; sending it again to the host that came back");
        CallOptions rest = retry;
        rest.timeout = std::max(Duration{1}, timeout - (clock.now() - started));
        return call_body(body, rest);
      }
    }
    throw;
  }
  if (!reply.ok() && reply.error().type == proto::error_type::kUnavailable &&
    options.allow_failover && fail_over(reply.host))
  {
    return call_body(body, retry);
  }
  if (reply.ok()) {
    return accepted(reply, body, costmap);
  }
  const proto::Error & error = reply.error();
  if (error.type == proto::error_type::kSessionUnknown && options.allow_resync) {
    reestablish(reply.host);
    CallOptions again = options;
    again.allow_resync = false;
    return call_body(body, again);
  }
  throw error_from_reply(error, config_.kind);
}

PluginSession::~PluginSession()
{
  if (cycle_) {
    cycle_->forget(*this);
  }
}

void PluginSession::join(std::shared_ptr<CarriedCycle> cycle)
{
  if (cycle_ && cycle_ != cycle) {
    cycle_->forget(*this);
  }
  cycle_ = std::move(cycle);
}

Duration PluginSession::timeout_of(const proto::RequestBody & body) const
{
  const Duration timeout = config_.timeouts.for_op(proto::op_of(body));
  if (const auto * smooth = std::get_if<proto::SmoothRequest>(&body)) {
    // the smoother is given max_time: its reply is awaited that long and the grace more
    return std::max(
      timeout, std::chrono::duration_cast<Duration>(
        std::chrono::duration<double>(smooth->max_time + proto::kSmoothGraceS)));
  }
  return timeout;
}

proto::Request PluginSession::request_for(proto::RequestBody body, CostmapAttached & costmap)
{
  proto::Request request;
  request.sid = sid_;
  request.epoch = state_.epoch;
  request.body = std::move(body);
  const proto::CostmapSent rule = proto::costmap_sent(request.op());
  if (rule != proto::CostmapSent::Never) {
    CostmapRead read = costmap_.read(
      rule == proto::CostmapSent::Always ? std::nullopt : state_.delivered_costmap);
    costmap = {read.version, read.costmap.has_value()};
    if (read.costmap) {
      set_costmap(request.body, std::move(*read.costmap));
    }
  }
  return request;
}

proto::ReplyBody PluginSession::accepted(
  proto::Reply & reply, const proto::RequestBody & body, const CostmapAttached & costmap)
{
  if (costmap.sent) {
    state_.delivered_costmap = costmap.version;
  }
  check_reply(body, reply.body(), reply.host);
  return std::get<proto::ReplyBody>(std::move(reply.outcome));
}

std::optional<Carried> PluginSession::prepare(proto::RequestBody body)
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  if (!state_.configured || !state_.established) {
    return std::nullopt;
  }
  Carried carried;
  carried.request = request_for(std::move(body), carried.costmap);
  try {
    carried.request.seq = state_.last_seq + 1;
    carried.payload = proto::encode_request(carried.request);
  } catch (const proto::EncodeError &) {
    return std::nullopt;  // the call on its own reports it
  }
  next_seq();
  return carried;
}

std::optional<proto::ReplyBody> PluginSession::settle(
  const Carried & carried, const std::optional<proto::Bytes> & answer)
{
  if (!answer) {
    return std::nullopt;
  }
  proto::Reply reply = checked_reply(*answer, carried.request, "carried reply");
  if (reply.ok()) {
    state_.last_host = reply.host;
    return accepted(reply, carried.request.body, carried.costmap);
  }
  const proto::Error & error = reply.error();
  if (error.type == proto::error_type::kSessionUnknown ||
    error.type == proto::error_type::kUnavailable)
  {
    return std::nullopt;
  }
  state_.last_host = reply.host;
  throw error_from_reply(error, config_.kind);
}

std::optional<proto::ReplyBody> PluginSession::take_body(
  Carried carried, const std::optional<proto::Bytes> & answer, proto::RequestBody body)
{
  if (state_.last_seq != carried.request.seq) {
    return std::nullopt;  // something else went on this session since: the host has moved on
  }
  if (const auto version = carried.costmap.version) {
    // Reading with the prepared version as the known one copies nothing when it is current.
    if (costmap_.read(version).version != *version) {
      return std::nullopt;  // call() would attach the newer costmap
    }
    // The same version, and the same delivered one (nothing sent since): call() would
    // attach the costmap the prepared request has, or none as it has none.
    move_costmap(carried.request.body, body);
  }
  proto::Request real;
  real.sid = sid_;
  real.epoch = state_.epoch;
  real.seq = carried.request.seq;
  real.body = std::move(body);
  try {
    if (proto::encode_request(real) != carried.payload) {
      return std::nullopt;
    }
  } catch (const proto::EncodeError &) {
    return std::nullopt;  // the call on its own reports it
  }
  return settle(carried, answer);
}

proto::Reply PluginSession::exchange(const proto::Request & request, const CallOptions & options)
{
  const proto::Op op = request.op();
  const std::string op_text(proto::op_name(op));
  proto::Bytes payload;
  try {
    payload = proto::encode_request(request);
  } catch (const proto::EncodeError & error) {
    fail(generic_error(config_.kind), Cause::Local, "cannot encode " + op_text + ": " + error.what());
  }
  const Duration timeout = options.timeout.value_or(timeout_of(request.body));
  WaitHook hook;
  const WaitHook * hook_ptr = nullptr;
  if (options.while_waiting) {
    hook.poll = [&options, seq = request.seq]() {options.while_waiting(seq);};
    hook_ptr = &hook;
  }
  const Clock & clock = transport_.hosts().clock();
  const TimePoint sent = clock.now();
  std::optional<proto::Bytes> answer;
  try {
    answer = transport_.query(target(keys_.call(op)), payload, timeout, hook_ptr);
  } catch (const CallError &) {
    throw;
  } catch (const std::exception & error) {
    fail(
      host_failure_error(config_.kind), Cause::Transport,
      op_text + " on " + keys_.prefix() + ": Zenoh query failed: " + error.what());
  }
  if (!answer) {
    // Zenoh ends a query early, with no reply, when the host it went to is gone.
    const Duration waited = clock.now() - sent;
    fail(
      host_failure_error(config_.kind), Cause::TimedOut,
      ended_before(waited, timeout) ?
      op_text + " got no reply from " + keys_.prefix() + ": the query ended after " +
      milliseconds(waited) + " ms of " + milliseconds(timeout) + " (its host went away)" :
      op_text + " got no reply from " + keys_.prefix() + " within " + milliseconds(timeout) +
      " ms");
  }
  proto::Reply reply = checked_reply(*answer, request, "reply");
  state_.last_host = reply.host;
  return reply;
}

proto::Reply PluginSession::checked_reply(
  const proto::Bytes & answer, const proto::Request & request, const std::string & what) const
{
  const std::string op_text(proto::op_name(request.op()));
  proto::Reply reply;
  try {
    reply = proto::decode_reply(answer, request.op());
  } catch (const proto::DecodeError & error) {
    fail(generic_error(config_.kind), Cause::BadReply, "bad " + what + " to " + op_text + ": " +
      error.what());
  }
  if (reply.seq != request.seq) {
    fail(
      generic_error(config_.kind), Cause::BadReply,
      what + " to " + op_text + " has seq " + std::to_string(reply.seq) + ", expected " +
      std::to_string(request.seq));
  }
  return reply;
}

void PluginSession::reestablish(const std::string & host)
{
  log(
    logger_, LogLevel::Warn,
    keys_.prefix() + ": host " + host + " does not know session " + sid_.substr(0, 8) +
    "; re-sending state");
  ++state_.resyncs;
  establish();
}

void PluginSession::pin_host()
{
  const HostWatcher::Hosts alive = transport_.hosts().alive();
  if (alive.empty() || alive.count(state_.pinned_host) != 0) {
    return;
  }
  const std::string & smallest = *alive.begin();
  if (!state_.pinned_host.empty()) {
    log(
      logger_, LogLevel::Warn,
      keys_.prefix() + ": host " + state_.pinned_host + " is gone; using " + smallest);
    ++state_.failovers;
  }
  state_.pinned_host = smallest;
}

bool PluginSession::fail_over(const std::string & avoid)
{
  HostWatcher::Hosts alive = transport_.hosts().alive();
  alive.erase(state_.pinned_host);
  alive.erase(avoid);
  if (alive.empty()) {
    return false;
  }
  log(
    logger_, LogLevel::Warn,
    keys_.prefix() + ": failing over from host " + state_.pinned_host + " to " + *alive.begin());
  state_.pinned_host = *alive.begin();
  ++state_.failovers;
  return true;
}

void PluginSession::establish()
{
  configure_locked();
  CallOptions options;
  options.allow_resync = false;
  try {
    if (state_.active) {
      call(proto::ActivateRequest{}, options);
    }
    for (const auto & [kind, op] : proto::kRestored) {
      if (kind != config_.kind) {
        continue;
      }
      if (std::optional<proto::RequestBody> body = restored(op)) {
        call_body(*body, options);
      }
    }
  } catch (const CallError &) {
    state_.established = false;  // the host lacks part of the state: the next call starts again
    throw;
  }
}

void PluginSession::fail(ErrorKind kind, Cause cause, const std::string & message) const
{
  throw CallError(kind, cause, message);
}

// --- state ----------------------------------------------------------------------------------

SessionState PluginSession::state() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  return state_;
}

proto::Params PluginSession::params() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  return config_.params;
}

Timeouts PluginSession::timeouts() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  return config_.timeouts;
}

void PluginSession::set_timeouts(const Timeouts & timeouts)
{
  std::lock_guard<std::recursive_mutex> lock(mutex_);
  config_.timeouts = timeouts;
}

}  // namespace nav2_pyif_bridge::client
