// Robots of `nav2-pyif-bench fleet --cpp-clients`: each a ControllerSession of the plugin's own
// client code on the plugin's ZenohTransport (one Zenoh session for the process, as for the
// plugins of one controller_server), calling compute_velocity_commands at a control rate. The
// Python clients cost the 2-core benchmark machine more CPU per call than the host does; these
// cost what the plugin costs a robot.
//
// The exchange with the benchmark, line by line:
//   stdout: "ready I" once robot I is configured, active, has its plan and one cycle worked
//           ("failed I WHY" when it could not be set up: every cycle of its run is a miss)
//   stdin:  "go NS": start at NS (CLOCK_REALTIME ns), robot I at NS + (I % 20) / 20 periods
//   stdout: at the end one JSON line {"samples": [[ns, ok], ...], "errors": ["...", ...]}
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/client/costmap_version.hpp"
#include "nav2_pyif_bridge/zenoh_transport.hpp"

#include "bench_zenoh.hpp"

namespace nav2_pyif_bench
{
namespace
{

namespace client = nav2_pyif_bridge::client;
namespace protocol = nav2_pyif_bridge::protocol;
using namespace std::chrono_literals;
using Wall = std::chrono::system_clock;

constexpr const char * kUsage =
  "usage: nav2_pyif_fleet_client --endpoint ENDPOINT --first I --count N --seconds S\n"
  "         [--rate HZ] [--param NAME=VALUE ...] [--scan FILE]\n"
  "  Robots I .. I+N-1 on keys nav2_pyif/robot<i>/FollowPath of the planner host at ENDPOINT.\n"
  "  --scan: a LaserScan's CDR bytes, sent as input 'scan' with every cycle.\n";

struct Options
{
  std::string endpoint;
  int first{0};
  int count{0};
  double seconds{5.0};
  double rate_hz{20.0};
  protocol::Params params;
  std::vector<std::uint8_t> scan;
};

// "30" -> int, "0.5" -> double, "true"/"false" -> bool, else the string: as a YAML scalar.
protocol::ParamValue param_value(const std::string & text)
{
  if (text == "true" || text == "false") {
    return text == "true";
  }
  std::size_t used = 0;
  try {
    const auto integer = std::stoll(text, &used);
    if (used == text.size()) {
      return std::int64_t{integer};
    }
    const auto real = std::stod(text, &used);
    if (used == text.size()) {
      return real;
    }
  } catch (const std::exception &) {
  }
  return text;
}

Options parse(int argc, char ** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      throw std::invalid_argument(arg + " needs a value");
    }
    const std::string value = argv[++i];
    if (arg == "--endpoint") {
      options.endpoint = value;
    } else if (arg == "--first") {
      options.first = std::stoi(value);
    } else if (arg == "--count") {
      options.count = std::stoi(value);
    } else if (arg == "--seconds") {
      options.seconds = std::stod(value);
    } else if (arg == "--rate") {
      options.rate_hz = std::stod(value);
    } else if (arg == "--param") {
      const auto eq = value.find('=');
      if (eq == std::string::npos) {
        throw std::invalid_argument("--param takes NAME=VALUE, got " + value);
      }
      options.params.set(value.substr(0, eq), param_value(value.substr(eq + 1)));
    } else if (arg == "--scan") {
      std::ifstream file(value, std::ios::binary);
      if (!file) {
        throw std::invalid_argument("cannot read --scan " + value);
      }
      options.scan.assign(std::istreambuf_iterator<char>(file), {});
    } else {
      throw std::invalid_argument("unknown option " + arg);
    }
  }
  if (options.endpoint.empty() || options.count < 1 || options.rate_hz <= 0) {
    throw std::invalid_argument("--endpoint and --count >= 1 are required");
  }
  return options;
}

// The benchmark's local costmap (fleet_planners.costmap): a free 100 x 100 grid at 5 cm,
// origin (-1.5, -2.5), a 0.4 x 0.3 m footprint.
class FleetCostmap : public client::CostmapSource
{
public:
  client::CostmapRead read(std::optional<std::uint64_t> known) override
  {
    client::CostmapView view;
    view.frame_id = "odom";
    view.size_x = view.size_y = 100;
    view.resolution = 0.05;
    view.origin_x = -1.5;
    view.origin_y = -2.5;
    view.data = cells_.data();
    view.footprint = {0.2, 0.15, 0.2, -0.15, -0.2, -0.15, -0.2, 0.15};
    return client::read_costmap(view, version_, known);
  }

private:
  std::vector<std::uint8_t> cells_ = std::vector<std::uint8_t>(100 * 100, 0);
  client::CostmapVersion version_;
};

// The benchmark's plan (fleet_planners.plan): 100 poses along x over 5 m.
protocol::Path plan()
{
  protocol::Path path;
  path.frame_id = "odom";
  for (int i = 0; i < 100; ++i) {
    path.poses.insert(path.poses.end(), {5.0 * i / 99.0, 0, 0, 0, 0, 0, 1});
  }
  return path;
}

std::int64_t wall_ns()
{
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
    Wall::now().time_since_epoch()).count();
}

struct Results
{
  std::mutex mutex;
  std::vector<std::pair<std::int64_t, bool>> samples;
  std::set<std::string> errors;
  std::mutex out;  // stdout lines from robot threads
};

class Robot
{
public:
  Robot(const Options & options, int index, Results & results)
  : options_(options), index_(index), results_(results),
    keys_("nav2_pyif/robot" + std::to_string(index) + "/FollowPath"),
    zenoh_(connect_to(options.endpoint), keys_), session_(config(options, keys_), zenoh_, costmap_)
  {
    pose_.frame_id = "odom";
    pose_.pose = {1.0, 0, 0, 0, 0, 0, 1};  // 1 m into the plan (fleet_planners.robot_pose)
  }

  // Set up, then one cycle that works (a dozen workers compiling at once may overrun).
  void start()
  {
    try {
      if (!session_.wait_for_host(300s)) {
        throw std::runtime_error("no planner host alive");
      }
      session_.configure();
      session_.activate();
      session_.set_plan(plan());
      const auto deadline = std::chrono::steady_clock::now() + 300s;
      for (;;) {
        try {
          cycle_once();
          break;
        } catch (const std::exception &) {
          if (std::chrono::steady_clock::now() > deadline) {
            throw;
          }
          std::this_thread::sleep_for(500ms);
        }
      }
      say("ready " + std::to_string(index_));
      ready_ = true;
    } catch (const std::exception & error) {
      say("failed " + std::to_string(index_) + " " + error.what());
    }
  }

  void run(std::int64_t go_ns)
  {
    const auto period =
      std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / options_.rate_hz));
    const auto cycles = static_cast<int>(options_.seconds * options_.rate_hz + 0.5);
    std::vector<std::pair<std::int64_t, bool>> samples;
    std::set<std::string> errors;
    if (!ready_) {  // never set up: every cycle of its run is a miss
      samples.assign(cycles, {period.count(), false});
      errors.insert("set-up failed");
    } else {
      auto timeouts = session_.timeouts();
      timeouts.call = period;  // the control loop's: a reply later than the period is a miss
      session_.set_timeouts(timeouts);
      const auto go = std::chrono::duration_cast<Wall::duration>(std::chrono::nanoseconds(go_ns));
      auto next = Wall::time_point(go) + (index_ % 20) * period / 20;
      for (int i = 0; i < cycles; ++i) {
        std::this_thread::sleep_until(next);
        const auto started = std::chrono::steady_clock::now();
        bool ok = true;
        try {
          cycle_once();
        } catch (const std::exception & error) {
          ok = false;
          const std::string what = error.what();
          errors.insert(what.substr(0, what.find('\n')));
        }
        samples.emplace_back((std::chrono::steady_clock::now() - started).count(), ok);
        next += period;
      }
    }
    const std::lock_guard<std::mutex> lock(results_.mutex);
    results_.samples.insert(results_.samples.end(), samples.begin(), samples.end());
    results_.errors.insert(errors.begin(), errors.end());
  }

  void stop()
  {
    try {
      session_.cleanup();
    } catch (const std::exception &) {
    }
  }

private:
  static client::SessionConfig config(const Options & options, const client::KeySpace & keys)
  {
    client::SessionConfig config;
    config.key_prefix = keys.prefix();
    config.name = "FollowPath";
    config.node = "nav2_pyif_fleet_client";
    config.global_frame = "odom";
    config.params = options.params;
    // dozens of robots set up at once: generous, as the Python clients' set-up
    config.timeouts.call = 10s;
    config.timeouts.lifecycle = 60s;
    config.timeouts.configure = 300s;
    return config;
  }

  void cycle_once()
  {
    static const std::array<double, 6> velocity{};
    if (!options_.scan.empty()) {  // a new scan with every cycle, as a 20 Hz laser gives
      protocol::Input scan;
      scan.name = "scan";
      scan.type = "sensor_msgs/msg/LaserScan";
      scan.stamp_ns = wall_ns();
      scan.cdr = options_.scan;
      session_.set_input(std::move(scan));
    }
    session_.compute_velocity_commands(pose_, velocity, std::nullopt);
  }

  void say(const std::string & line)
  {
    const std::lock_guard<std::mutex> lock(results_.out);
    std::cout << line << std::endl;
  }

  const Options & options_;
  int index_;
  Results & results_;
  client::KeySpace keys_;
  nav2_pyif_bridge::ZenohTransport zenoh_;
  FleetCostmap costmap_;
  client::ControllerSession session_;
  protocol::PoseStamped pose_;
  bool ready_{false};
};

std::string json_string(const std::string & text)
{
  std::ostringstream out;
  out << '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out << ' ';
    } else {
      out << c;
    }
  }
  out << '"';
  return out.str();
}

int run(const Options & options)
{
  Results results;
  std::vector<std::unique_ptr<Robot>> robots;
  for (int i = 0; i < options.count; ++i) {
    robots.push_back(std::make_unique<Robot>(options, options.first + i, results));
  }
  {
    std::vector<std::thread> setting_up;
    for (auto & robot : robots) {
      setting_up.emplace_back([&robot] {robot->start();});
    }
    for (auto & thread : setting_up) {
      thread.join();
    }
  }
  std::string word;
  std::int64_t go_ns = 0;
  if (!(std::cin >> word >> go_ns) || word != "go") {
    std::cerr << "nav2_pyif_fleet_client: expected 'go NS' on stdin" << std::endl;
    return 2;
  }
  std::vector<std::thread> running;
  for (auto & robot : robots) {
    running.emplace_back([&robot, go_ns] {robot->run(go_ns);});
  }
  for (auto & thread : running) {
    thread.join();
  }
  for (auto & robot : robots) {
    robot->stop();
  }
  std::ostringstream json;
  json << "{\"samples\": [";
  for (std::size_t i = 0; i < results.samples.size(); ++i) {
    json << (i ? ", [" : "[") << results.samples[i].first << ", "
         << (results.samples[i].second ? "true" : "false") << "]";
  }
  json << "], \"errors\": [";
  std::size_t n = 0;
  for (const auto & error : results.errors) {
    json << (n++ ? ", " : "") << json_string(error);
  }
  json << "]}";
  std::cout << json.str() << std::endl;
  return 0;
}

}  // namespace
}  // namespace nav2_pyif_bench

int main(int argc, char ** argv)
{
  try {
    return nav2_pyif_bench::run(nav2_pyif_bench::parse(argc, argv));
  } catch (const std::invalid_argument & error) {
    std::cerr << "nav2_pyif_fleet_client: " << error.what() << "\n" << nav2_pyif_bench::kUsage;
    return 2;
  }
}
