#include "nav2_pyif_bridge/zenoh_transport.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <utility>

#include "zenoh.hxx"

namespace nav2_pyif_bridge
{
namespace
{

using client::LogLevel;
constexpr const char * kConfigEnv = "NAV2_PYIF_ZENOH_CONFIG";
#if defined(ZENOHCXX_ZENOHPICO)
constexpr const char * kDefaultRouter = "tcp/localhost:7447";  // no config files here
#endif

std::string json_string_list(const std::vector<std::string> & items)
{
  std::string out = "[";
  for (const auto & item : items) {
    out += (out.size() > 1 ? ",\"" : "\"") + item + "\"";
  }
  return out + "]";
}

std::string config_file(const ZenohOptions & options)
{
  if (!options.config_file.empty()) {
    return options.config_file;
  }
  const char * env = std::getenv(kConfigEnv);
  return env ? env : "";
}

zenoh::Config make_config(const ZenohOptions & options)
{
  const std::string file = config_file(options);
#if defined(ZENOHCXX_ZENOHPICO)
  if (!file.empty()) {
    throw std::invalid_argument(
            "zenoh_config / $" + std::string(kConfigEnv) + " (" + file + "): JSON5 config files "
            "need zenoh-cpp's zenoh-c backend; this plugin was built with zenoh-pico: set "
            "zenoh_connect instead");
  }
  zenoh::Config config = zenoh::Config::create_default();
  config.insert(Z_CONFIG_MODE_KEY, "client");
  const std::string endpoint = options.connect.empty() ? kDefaultRouter : options.connect.front();
  config.insert(Z_CONFIG_CONNECT_KEY, endpoint.c_str());
  config.insert(Z_CONFIG_MULTICAST_SCOUTING_KEY, "false");
  return config;
#else
  // The package's default session when no file is named (share/nav2_pyif_bridge/config/
  // default_session.json5), loaded as rmw_zenoh loads its DEFAULT_RMW_ZENOH_SESSION_CONFIG
  // .json5: a client of tcp/localhost:7447 with the planner host's lease and retry (generated
  // from nav2_pyif_protocol/zenoh/client.json5).
  zenoh::Config config = zenoh::Config::from_file(
    file.empty() ? NAV2_PYIF_DEFAULT_ZENOH_CONFIG : file);
  if (!options.connect.empty()) {
    config.insert_json5("connect/endpoints", json_string_list(options.connect));
  }
  return config;
#endif
}

std::string describe(const ZenohOptions & options)
{
#if defined(ZENOHCXX_ZENOHPICO)
  return options.connect.empty() ? kDefaultRouter : options.connect.front();
#else
  const std::string file = config_file(options);
  std::string out = file.empty() ? "the default config" : "config file " + file;
  for (const auto & endpoint : options.connect) {
    out += ", " + endpoint;
  }
  return out;
#endif
}

// One session per configuration and server (owner), shared by that server's plugins, and kept
// until the process ends: closing a zenoh-pico (1.9) session whose peer went away and came back can
// block forever in z_session_drop, which would hang Nav2's cleanup and shutdown. The OS closes
// the connection at exit. (Never destroyed, so no exit-time destructor can block either.)
struct SharedSessions
{
  std::mutex mutex;
  std::map<std::string, std::shared_ptr<zenoh::Session>> by_id;

  static SharedSessions & instance()
  {
    static auto * sessions = new SharedSessions;
    return *sessions;
  }
  static std::string id_of(const ZenohOptions & options)
  {
    return options.owner + "|" + config_file(options) + "|" + json_string_list(options.connect);
  }
  // The session the plugins of `options` share now (null: none opened yet).
  std::shared_ptr<zenoh::Session> current(const ZenohOptions & options)
  {
    std::lock_guard<std::mutex> lock(mutex);
    return by_id[id_of(options)];
  }
};

std::shared_ptr<zenoh::Session> open_shared_session(const ZenohOptions & options)
{
  auto & shared = SharedSessions::instance();
  std::lock_guard<std::mutex> lock(shared.mutex);
  auto & session = shared.by_id[SharedSessions::id_of(options)];
  if (!session) {
    session = std::make_shared<zenoh::Session>(zenoh::Session::open(make_config(options)));
  }
  return session;
}

#if defined(ZENOHCXX_ZENOHPICO)
// zenoh-pico (1.9) reconnects a client session by itself, but gives up for good when an attempt
// reaches a peer that takes the connection and never answers it (a host stopped, or busy
// swapping, while its port still accepts): the session stays open, connected to nothing, and
// the plugin would never see its host again. Reproduced with a host stopped for 30 s (a 5 s stop
// recovered by itself); most likely the same in nav2_bringup's composed container under load,
// after a 2 s stop. Such a session is replaced by a new one once it has been connected to
// nothing this long: a reconnection of its own, when it works, takes about a second.
constexpr bool kWatchesSession = true;
constexpr auto kReopenAfter = std::chrono::seconds(5);
// A session can also stay deaf while zenoh-pico says it is connected: seen in Lyrical's composed
// bringup after a 2 s stop of the host (its lease ran out meanwhile). planner_server's plugin
// logged the host gone and never saw it again, and a new liveliness subscriber on that session
// heard nothing either, while the other plugins reached the same host. A session on which a host
// was alive, and none has been for this long, is replaced once as a stranded one is; not again
// until a host is seen (a host that is really gone is not chased with new sessions).
constexpr auto kDeafAfter = std::chrono::seconds(5);
// What is wrong with a session replaced for either reason, for the log.
const std::string kStranded = "was connected to nothing for " +
  std::to_string(kReopenAfter.count()) + " s and did not reconnect by itself";
const std::string kDeaf = "has been connected for " + std::to_string(kDeafAfter.count()) +
  " s with no planner host heard, after one was: it went deaf";

bool connected_to_nothing(const zenoh::Session & session)
{
  zenoh::ZResult err = Z_OK;
  const bool none = session.get_routers_z_id(&err).empty();  // a client's link (the only one)
  return none && err == Z_OK;  // an error says nothing either way
}

// A replaced session is closed, so that a reconnection of its own cannot come back beside its
// replacement, on a thread of its own (a zenoh-pico close can block, as above), and then kept,
// never destroyed, for the same reason.
void retire(std::shared_ptr<zenoh::Session> session)
{
  std::thread(
    [session = std::move(session)]() mutable {
      zenoh::ZResult err = Z_OK;
      session->close(zenoh::Session::SessionCloseOptions::create_default(), &err);
      new std::shared_ptr<zenoh::Session>(std::move(session));  // never destroyed
    }).detach();
}

// The session the plugins of `options` share now, and whether this call opened it: `stranded`
// replaced by a new one (the caller retires it), unless a plugin sharing it did that already.
// Throws as Session::open does (the host still unreachable).
std::pair<std::shared_ptr<zenoh::Session>, bool> reopen_shared_session(
  const ZenohOptions & options, const std::shared_ptr<zenoh::Session> & stranded)
{
  auto & shared = SharedSessions::instance();
  if (auto now = shared.current(options); now != stranded) {
    return {now, false};
  }
  // Opened unlocked: an open that waits on an unanswering host holds up no other plugin.
  auto fresh = std::make_shared<zenoh::Session>(zenoh::Session::open(make_config(options)));
  std::lock_guard<std::mutex> lock(shared.mutex);
  auto & session = shared.by_id[SharedSessions::id_of(options)];
  if (session != stranded) {  // another plugin's keeper was quicker
    retire(std::move(fresh));
    return {session, false};
  }
  session = std::move(fresh);
  return {session, true};
}

#else
constexpr bool kWatchesSession = false;  // zenoh-c reconnects for as long as it takes
#endif

// Every query goes to all matching queryables (replicas drop what is not theirs: host=<id>).
zenoh::Session::GetOptions get_options(const protocol::Bytes & payload, client::Duration timeout)
{
  zenoh::Session::GetOptions options;
  options.target = Z_QUERY_TARGET_ALL;
  options.payload = zenoh::Bytes(payload);
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(timeout).count();
  options.timeout_ms = static_cast<std::uint64_t>(std::max<std::int64_t>(1, ms));
  return options;
}

// A host appearing or going is worth a line in Nav2's log: it dates a crash, a lost link (its
// token withdrawn one Zenoh lease after the last packet) and the moment service came back.
client::HostWatcher::OnChange host_change_logger(client::Logger logger, std::string prefix)
{
  return [logger = std::move(logger), prefix = std::move(prefix)](
    const std::string & host, bool alive) {
           client::log(
             logger, alive ? LogLevel::Info : LogLevel::Warn,
             "planner host " + host + (alive ? " is alive on " : " is gone from ") + prefix);
         };
}

}  // namespace

const char * zenoh_backend() noexcept
{
#if defined(ZENOHCXX_ZENOHPICO)
  return "zenoh-pico";
#else
  return "zenoh-c";
#endif
}

struct ZenohTransport::Link
{
  std::shared_ptr<zenoh::Session> session;
  std::optional<zenoh::Subscriber<void>> hosts;
  // Set when the link is replaced: its subscriber's samples no longer count.
  std::shared_ptr<std::atomic<bool>> retired = std::make_shared<std::atomic<bool>>(false);

  ~Link()
  {
    hosts.reset();  // undeclare before the session may go
  }
};

ZenohTransport::ZenohTransport(
  ZenohOptions options, const client::KeySpace & keys, client::Logger logger)
: options_(std::move(options)), hosts_key_(keys.hosts()), logger_(std::move(logger)),
  where_(describe(options_)),
  watcher_(std::make_shared<client::HostWatcher>(
      client::SteadyClock::instance(), host_change_logger(logger_, keys.prefix())))
{
  (void)make_config(options_);  // refuse what this backend cannot do, now
  if (!try_open(false) || kWatchesSession) {
    keeper_ = std::thread([this]() {keep_linked();});
  }
}

ZenohTransport::~ZenohTransport()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (keeper_.joinable()) {
    keeper_.join();
  }
  std::unique_ptr<Link> link;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    link = std::move(link_);
  }
  link.reset();
}

std::unique_ptr<ZenohTransport::Link> ZenohTransport::link_on(
  std::shared_ptr<zenoh::Session> session) const
{
  auto link = std::make_unique<Link>();
  link->session = std::move(session);
  zenoh::Session::LivelinessSubscriberOptions subscriber_options;
  subscriber_options.history = true;  // the tokens alive before this subscriber, too
  std::weak_ptr<client::HostWatcher> watcher = watcher_;
  link->hosts.emplace(
    link->session->liveliness_declare_subscriber(
      zenoh::KeyExpr(hosts_key_),
      [watcher, retired = link->retired](zenoh::Sample & sample) {
        auto w = watcher.lock();
        if (w && !retired->load()) {
          w->on_token(
            client::KeySpace::host_id_of(sample.get_keyexpr().as_string_view()),
            sample.get_kind() == Z_SAMPLE_KIND_PUT);
        }
      },
      []() {}, std::move(subscriber_options)));
  return link;
}

bool ZenohTransport::try_open(bool quiet)
{
  std::unique_ptr<Link> link;
  try {
    link = link_on(open_shared_session(options_));
  } catch (const std::exception & error) {
    client::log(
      logger_, quiet ? LogLevel::Debug : LogLevel::Warn,
      std::string("cannot open a Zenoh session (") + zenoh_backend() + ", " + where_ + "): " +
      error.what() + "; retrying every second");
    return false;
  }
  client::log(
    logger_, LogLevel::Info,
    std::string("Zenoh session open (") + zenoh_backend() + ", " + where_ + "), watching " +
    hosts_key_);
  std::lock_guard<std::mutex> lock(mutex_);
  link_ = std::move(link);
  return true;
}

#if defined(ZENOHCXX_ZENOHPICO)
bool ZenohTransport::try_reopen(
  const std::shared_ptr<zenoh::Session> & stranded, const std::string & why)
{
  std::shared_ptr<zenoh::Session> session;
  bool opened_here = false;
  try {
    std::tie(session, opened_here) = reopen_shared_session(options_, stranded);
  } catch (const std::exception & error) {
    client::log(
      logger_, LogLevel::Debug,
      "cannot open a new Zenoh session (" + where_ + "): " + error.what() + "; retrying");
    return false;
  }
  // The old link goes deaf before the new one hears: a token withdrawn as the old session
  // closes must not follow the new session's "alive".
  std::unique_lock<std::mutex> lock(mutex_);
  link_->retired->store(true);
  lock.unlock();
  if (opened_here) {
    retire(stranded);
  }
  std::unique_ptr<Link> link;
  try {
    link = link_on(session);
  } catch (const std::exception & error) {
    client::log(
      logger_, LogLevel::Warn,
      "cannot watch " + hosts_key_ + " on the new Zenoh session (" + where_ + "): " +
      error.what() + "; retrying");
    return false;  // the next try adopts the new session (SharedSessions::current)
  }
  lock.lock();
  std::unique_ptr<Link> old = std::exchange(link_, std::move(link));
  lock.unlock();
  // Kept, never destroyed: its subscriber is not undeclared on the retired session.
  static_cast<void>(old.release());
  client::log(
    logger_, opened_here ? LogLevel::Warn : LogLevel::Info,
    opened_here ?
    "the Zenoh session (zenoh-pico, " + where_ + ") " + why + "; a new one is open, watching " +
    hosts_key_ :
    "watching " + hosts_key_ + " on the new Zenoh session another plugin of this server opened");
  return true;
}
#endif

void ZenohTransport::keep_linked()
{
  using Clock = std::chrono::steady_clock;
  std::unique_lock<std::mutex> lock(mutex_);
  // Since when the session has been connected to nothing; epoch: it is connected.
  [[maybe_unused]] Clock::time_point stranded_since{};
  // Since when it has been connected with no host alive, after one was (epoch: not so).
  [[maybe_unused]] Clock::time_point deaf_since{};
  [[maybe_unused]] bool heard_a_host = false;
  while (!stop_cv_.wait_for(lock, std::chrono::seconds(1), [this]() {return stopping_;})) {
    const auto session = link_ ? link_->session : nullptr;
    lock.unlock();
    if (!session) {
      if (try_open(true) && !kWatchesSession) {
        return;
      }
#if defined(ZENOHCXX_ZENOHPICO)
    } else if (SharedSessions::instance().current(options_) != session) {
      try_reopen(session, "");  // another plugin of this server reopened the session they share
    } else if (!connected_to_nothing(*session)) {
      stranded_since = {};
      if (watcher_->any_alive()) {
        heard_a_host = true;
        deaf_since = {};
      } else if (heard_a_host && deaf_since == Clock::time_point{}) {
        deaf_since = Clock::now();
      } else if (
        heard_a_host && Clock::now() - deaf_since >= kDeafAfter && try_reopen(session, kDeaf))
      {
        heard_a_host = false;
        deaf_since = {};
      }
    } else if (stranded_since == Clock::time_point{}) {
      stranded_since = Clock::now();
    } else if (Clock::now() - stranded_since >= kReopenAfter && try_reopen(session, kStranded)) {
      stranded_since = {};
#endif
    }
    lock.lock();
  }
}

std::shared_ptr<zenoh::Session> ZenohTransport::session() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return link_ ? link_->session : nullptr;
}

std::optional<protocol::Bytes> ZenohTransport::query(
  const client::Target & target, const protocol::Bytes & payload, client::Duration timeout,
  const client::WaitHook * hook)
{
  const auto session = this->session();
  if (!session) {
    return std::nullopt;
  }
  struct Pending
  {
    std::mutex mutex;
    std::condition_variable cv;
    std::optional<protocol::Bytes> reply;
    bool done{false};
  };
  auto pending = std::make_shared<Pending>();
  session->get(
    zenoh::KeyExpr(target.key), target.parameters(),
    [pending, logger = logger_, key = target.key](zenoh::Reply & reply) {
      if (!reply.is_ok()) {
        // Not a host's answer (a host answers errors inside its reply), but it says why the
        // call may end with none: the session's or a router's error.
        client::log(
          logger, LogLevel::Warn,
          "Zenoh error reply to " + key + ": " + reply.get_err().get_payload().as_string());
        return;
      }
      std::lock_guard<std::mutex> lock(pending->mutex);
      if (!pending->reply) {
        pending->reply = reply.get_ok().get_payload().as_vector();
        pending->cv.notify_all();
      }
    },
    [pending]() {
      std::lock_guard<std::mutex> lock(pending->mutex);
      pending->done = true;
      pending->cv.notify_all();
    },
    get_options(payload, timeout));

  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::unique_lock<std::mutex> lock(pending->mutex);
  for (;;) {
    auto until = deadline;
    if (hook && hook->poll) {
      until = std::min(deadline, std::chrono::steady_clock::now() + hook->period);
    }
    pending->cv.wait_until(lock, until, [&]() {return pending->reply || pending->done;});
    if (pending->reply) {
      return std::move(pending->reply);
    }
    if (pending->done || std::chrono::steady_clock::now() >= deadline) {
      return std::nullopt;
    }
    lock.unlock();
    hook->poll();
    lock.lock();
  }
}

void ZenohTransport::send(
  const client::Target & target, const protocol::Bytes & payload, client::Duration timeout)
{
  const auto session = this->session();
  if (!session) {
    return;
  }
  session->get(
    zenoh::KeyExpr(target.key), target.parameters(), [](zenoh::Reply &) {}, []() {},
    get_options(payload, timeout));
}

}  // namespace nav2_pyif_bridge
