#include "pyif_rows.hpp"

#include <array>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <utility>

#include "bench_zenoh.hpp"

namespace nav2_pyif_bench
{

using namespace std::chrono_literals;

namespace
{

constexpr std::uint32_t kGridSize = 10;
constexpr double kResolution = 0.05;
constexpr std::size_t kPlanPoses = 20;  // the plan set at start
constexpr std::size_t kLongPlanPoses = 1000;  // the plan row's, as protocol_bench's
// As protocol_bench's TIMEOUTS: generous, so a loaded machine shows slow calls, not failures.
constexpr client::Duration kCallTimeout = 2s;

client::SessionConfig session_config(const std::string & key)
{
  client::SessionConfig config;
  config.key_prefix = key;
  config.name = "FollowPath";
  config.node = "nav2_pyif_cycle_bench";
  config.global_frame = "odom";
  config.timeouts.call = kCallTimeout;
  return config;
}

protocol::Path straight_plan(std::size_t poses)
{
  protocol::Path path;
  path.frame_id = "odom";
  for (std::size_t i = 0; i < poses; ++i) {
    path.poses.insert(path.poses.end(), {0.05 * static_cast<double>(i), 0, 0, 0, 0, 0, 1});
  }
  return path;
}

}  // namespace

std::optional<protocol::Bytes> TimedTransport::query(
  const client::Target & target, const protocol::Bytes & payload, client::Duration timeout,
  const client::WaitHook * hook)
{
  const auto start = BenchClock::now();
  auto reply = inner_.query(target, payload, timeout, hook);
  last_query_ns_ = elapsed_ns(start);
  if (reply) {
    last_reply_ = *reply;
  } else {
    last_reply_.clear();
  }
  return reply;
}

FixedCostmap::FixedCostmap()
: cells_(std::size_t{kGridSize} * kGridSize, 0)
{
}

client::CostmapRead FixedCostmap::read(std::optional<std::uint64_t> known)
{
  client::CostmapView view;
  view.frame_id = "odom";
  view.size_x = view.size_y = kGridSize;
  view.resolution = kResolution;
  view.origin_x = view.origin_y = -10.0;
  view.data = cells_.data();
  view.robot_radius = 0.2;
  return client::read_costmap(view, version_, known);
}

PyifCycle::PyifCycle(const std::string & endpoint, const std::string & key, client::Logger logger)
: keys_(key), zenoh_(connect_to(endpoint), keys_, logger), timed_(zenoh_),
  session_(session_config(key), timed_, costmap_, logger)
{
  pose_.frame_id = "odom";
  long_plan_ = straight_plan(kLongPlanPoses);
  protocol::Request unknown;
  unknown.sid = client::new_session_id();  // a valid sid no host has seen
  unknown.seq = 1;
  unknown.body = protocol::ActivateRequest{};
  unknown_request_ = protocol::encode_request(unknown);
}

void PyifCycle::start(client::Duration wait_for_host)
{
  if (!session_.wait_for_host(wait_for_host)) {
    throw std::runtime_error("no planner host alive under " + keys_.prefix());
  }
  session_.configure();
  session_.activate();
  session_.set_plan(straight_plan(kPlanPoses));
}

template<class Call>
Sample PyifCycle::timed(protocol::Op op, Call && call)
{
  Sample sample;
  const auto start = BenchClock::now();
  call();
  sample.total_ns = elapsed_ns(start);
  sample.query_ns = timed_.last_query_ns();
  // Decoded again outside the timed call, only to read what the host reported.
  sample.handler_ns = protocol::decode_reply(timed_.last_reply(), op).compute_ns;
  return sample;
}

Sample PyifCycle::cycle()
{
  static const std::array<double, 6> velocity{};
  return timed(
    protocol::Op::ComputeVelocityCommands,
    [this] {session_.compute_velocity_commands(pose_, velocity, std::nullopt);});
}

Sample PyifCycle::plan()
{
  return timed(
    protocol::Op::SetPlan, [this] {
      if (auto error = session_.set_plan(long_plan_)) {
        throw std::runtime_error("set_plan failed: " + std::string(error->what()));
      }
    });
}

Sample PyifCycle::unknown_session()
{
  const client::Target target{keys_.call(protocol::Op::Activate), ""};
  const auto start = BenchClock::now();
  const auto reply = zenoh_.query(target, unknown_request_, kCallTimeout, nullptr);
  Sample sample{elapsed_ns(start)};
  if (!reply) {
    throw std::runtime_error("no reply from " + target.key);
  }
  return sample;
}

void PyifCycle::stop()
{
  session_.cleanup();
}

BareGet::BareGet(const std::string & endpoint, const std::string & key, client::Logger logger)
: key_(key), zenoh_(connect_to(endpoint), client::KeySpace(key), std::move(logger))
{
}

void BareGet::start(client::Duration wait)
{
  const auto deadline = BenchClock::now() + wait;
  for (;;) {
    if (zenoh_.query(client::Target{key_, ""}, {}, 200ms, nullptr)) {
      return;
    }
    if (BenchClock::now() > deadline) {
      throw std::runtime_error("the bare queryable " + key_ + " did not answer");
    }
    std::this_thread::sleep_for(50ms);  // not connected yet: no get was sent
  }
}

Sample BareGet::get()
{
  const auto start = BenchClock::now();
  const auto reply = zenoh_.query(client::Target{key_, ""}, {}, kCallTimeout, nullptr);
  Sample sample{elapsed_ns(start)};
  if (!reply) {
    throw std::runtime_error("no reply from the bare queryable " + key_);
  }
  return sample;
}

}  // namespace nav2_pyif_bench
