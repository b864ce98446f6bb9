// The control cycle of `nav2-pyif-bench protocol` with the C++ plugin's own client code on
// the client side (in production the client is this plugin, not the Python reference
// client). Rows, each given on the command line, measured in interleaved rounds so drift hits
// all alike:
//   bare         the plugin's Zenoh get -> bench's bare_zenoh.py replying an empty payload
//   host_floor   an activate of an unknown session -> the host's cheapest reply
//   pyif         ControllerSession::compute_velocity_commands -> planner-host (worker process)
//   pyif_plan    ControllerSession::set_plan of a 1000-pose plan -> the same host
//   pyif_inproc  the same -> planner-host --isolation none
//   rclcpp       nav_msgs/Odometry -> rclpy_node.py -> geometry_msgs/TwistStamped
// With --paced-calls N, each row but host_floor is then measured again at a real control rate
// (--rate, 20 Hz: Nav2's default controller_frequency), the rows' calls spread over the period
// so every call starts from an idle client and host, as in Nav2: rows <row>.paced.
// The peers are started by `nav2-pyif-bench cpp-cycle`, which reads the samples this prints
// on stdout as JSON (progress goes to stderr):
//   {"backend": "...", "rows": {"bare": [ns, ...], "pyif": [...], "pyif.query": [...], ...}}
// where <row>.query is the Zenoh get inside a call and <row>.handler the host's handler time.
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "pyif_rows.hpp"
#include "rclcpp_topic_client.hpp"

namespace nav2_pyif_bench
{
namespace
{

using namespace std::chrono_literals;

constexpr const char * kUsage =
  "usage: nav2_pyif_cycle_bench [--bare ENDPOINT --bare-key KEY] [--host ENDPOINT --key KEY]\n"
  "         [--inproc ENDPOINT --inproc-key KEY] [--rclcpp] [--rounds N] [--calls N]\n"
  "         [--warmup N] [--wait SECONDS] [--paced-calls N] [--rate HZ]\n"
  "  ENDPOINT: where the peer listens (tcp/127.0.0.1:PORT); each row has its own session.\n"
  "  --host also measures host_floor. --rclcpp needs rclpy_node.py on the same ROS domain.\n";

struct Options
{
  std::string bare, bare_key{"nav2_pyif/bench/bare"};
  std::string host, key{"nav2_pyif/bench/FollowPath"};
  std::string inproc, inproc_key{"nav2_pyif/bench/InProcess"};
  bool rclcpp{false};
  int rounds{10};
  int calls{300};
  int warmup{50};
  int paced_calls{0};
  double rate_hz{20.0};
  double wait_s{30.0};
};

Options parse(int argc, char ** argv)
{
  Options o;
  const std::map<std::string, std::string *> strings{
    {"--bare", &o.bare}, {"--bare-key", &o.bare_key}, {"--host", &o.host}, {"--key", &o.key},
    {"--inproc", &o.inproc}, {"--inproc-key", &o.inproc_key}};
  const std::map<std::string, int *> ints{
    {"--rounds", &o.rounds}, {"--calls", &o.calls}, {"--warmup", &o.warmup},
    {"--paced-calls", &o.paced_calls}};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--rclcpp") {
      o.rclcpp = true;
      continue;
    }
    if (i + 1 >= argc) {
      throw std::invalid_argument(arg + " needs a value (or is unknown)");
    }
    const std::string value = argv[++i];
    if (auto s = strings.find(arg); s != strings.end()) {
      *s->second = value;
    } else if (auto n = ints.find(arg); n != ints.end()) {
      *n->second = std::stoi(value);
    } else if (arg == "--wait") {
      o.wait_s = std::stod(value);
    } else if (arg == "--rate") {
      o.rate_hz = std::stod(value);
    } else {
      throw std::invalid_argument("unknown option " + arg);
    }
  }
  if (o.rounds < 1 || o.calls < 1 || o.warmup < 0 || o.paced_calls < 0 || !(o.rate_hz > 0)) {
    throw std::invalid_argument(
            "--rounds and --calls must be >= 1, --warmup and --paced-calls >= 0, --rate > 0");
  }
  return o;
}

void progress(const std::string & message)
{
  std::cerr << "  … " << message << std::endl;
}

client::Logger stderr_logger()
{
  return [](client::LogLevel level, const std::string & message) {
           if (level >= client::LogLevel::Warn) {
             std::cerr << "[nav2_pyif_cycle_bench] " << message << std::endl;
           }
         };
}

struct Row
{
  std::string name;
  std::function<Sample()> run;
};

using Samples = std::map<std::string, std::vector<std::int64_t>>;

Samples interleaved(const std::vector<Row> & rows, const Options & o)
{
  for (const auto & row : rows) {
    for (int i = 0; i < o.warmup; ++i) {
      row.run();
    }
  }
  Samples samples;
  for (int r = 0; r < o.rounds; ++r) {
    progress("control cycle: round " + std::to_string(r + 1) + "/" + std::to_string(o.rounds));
    for (const auto & row : rows) {
      for (int i = 0; i < o.calls; ++i) {
        const Sample s = row.run();
        samples[row.name].push_back(s.total_ns);
        if (s.query_ns >= 0) {
          samples[row.name + ".query"].push_back(s.query_ns);
        }
        if (s.handler_ns >= 0) {
          samples[row.name + ".handler"].push_back(s.handler_ns);
        }
      }
    }
  }
  return samples;
}

// Each row once per period, the rows' calls evenly spread over it: between two calls of a row
// its client and peer sleep for a whole period, as a controller server's do between cycles.
void paced(const std::vector<Row> & rows, const Options & o, Samples & samples)
{
  std::vector<const Row *> paced_rows;
  for (const auto & row : rows) {
    if (row.name != "host_floor") {
      paced_rows.push_back(&row);
    }
  }
  if (o.paced_calls == 0 || paced_rows.empty()) {
    return;
  }
  const auto period = std::chrono::duration_cast<BenchClock::duration>(
    std::chrono::duration<double>(1.0 / o.rate_hz));
  const auto slot = period / static_cast<int>(paced_rows.size());
  progress(
    "control cycle at " + std::to_string(o.rate_hz) + " Hz: " + std::to_string(o.paced_calls) +
    " calls per row");
  auto next = BenchClock::now() + period;
  for (int i = 0; i < o.paced_calls; ++i, next += period) {
    for (std::size_t k = 0; k < paced_rows.size(); ++k) {
      std::this_thread::sleep_until(next + slot * static_cast<int>(k));
      samples[paced_rows[k]->name + ".paced"].push_back(paced_rows[k]->run().total_ns);
    }
  }
}

void print_json(const Samples & samples)
{
  std::string out = std::string("{\"backend\": \"") + nav2_pyif_bridge::zenoh_backend() +
    "\", \"rows\": {";
  bool first_row = true;
  for (const auto & [name, values] : samples) {
    out += (first_row ? "\"" : ", \"") + name + "\": [";
    first_row = false;
    for (std::size_t i = 0; i < values.size(); ++i) {
      out += (i ? "," : "") + std::to_string(values[i]);
    }
    out += "]";
  }
  out += "}}\n";
  std::fwrite(out.data(), 1, out.size(), stdout);
  std::fflush(stdout);
}

int run(const Options & o)
{
  const auto wait = std::chrono::duration_cast<client::Duration>(
    std::chrono::duration<double>(o.wait_s));
  std::unique_ptr<BareGet> bare;
  std::unique_ptr<PyifCycle> host, inproc;
  std::unique_ptr<RclcppTopicClient> ros;
  std::vector<Row> rows;
  // Row order within a round as in protocol_bench.
  if (!o.bare.empty()) {
    progress("waiting for the bare queryable at " + o.bare);
    bare = std::make_unique<BareGet>(o.bare, o.bare_key, stderr_logger());
    bare->start(wait);
    rows.push_back({"bare", [&] {return bare->get();}});
  }
  const auto start_cycle = [&](const std::string & endpoint, const std::string & key) {
      progress("waiting for the planner host " + key + " at " + endpoint);
      auto cycle = std::make_unique<PyifCycle>(endpoint, key, stderr_logger());
      cycle->start(wait);
      return cycle;
    };
  if (!o.host.empty()) {
    host = start_cycle(o.host, o.key);
    rows.push_back({"host_floor", [&] {return host->unknown_session();}});
    rows.push_back({"pyif", [&] {return host->cycle();}});
    rows.push_back({"pyif_plan", [&] {return host->plan();}});
  }
  if (!o.inproc.empty()) {
    inproc = start_cycle(o.inproc, o.inproc_key);
    rows.push_back({"pyif_inproc", [&] {return inproc->cycle();}});
  }
  if (o.rclcpp) {
    progress("waiting for the rclpy node (DDS discovery)");
    ros = std::make_unique<RclcppTopicClient>();
    if (!ros->wait_ready(wait)) {
      throw std::runtime_error("the rclpy node did not answer (DDS discovery, ROS_DOMAIN_ID?)");
    }
    rows.push_back(
      {"rclcpp", [&] {
          if (auto s = ros->cycle(1s)) {
            return *s;
          }
          throw std::runtime_error("the rclpy node did not answer within 1 s");
        }});
  }
  if (rows.empty()) {
    throw std::invalid_argument("no row given");
  }
  Samples samples = interleaved(rows, o);
  paced(rows, o, samples);
  for (auto * session : {host.get(), inproc.get()}) {
    if (session) {
      session->stop();
    }
  }
  print_json(samples);
  return 0;
}

}  // namespace
}  // namespace nav2_pyif_bench

int main(int argc, char ** argv)
{
  using nav2_pyif_bench::Options;
  Options options;
  try {
    options = nav2_pyif_bench::parse(argc, argv);
  } catch (const std::exception & error) {
    std::cerr << error.what() << "\n" << nav2_pyif_bench::kUsage;
    return 2;
  }
  if (options.rclcpp) {
    // No signal handlers: a SIGTERM from the bench driver ends this process at once.
    rclcpp::init(1, argv, rclcpp::InitOptions(), rclcpp::SignalHandlerOptions::None);
  }
  int code = 1;
  try {
    code = nav2_pyif_bench::run(options);
  } catch (const std::exception & error) {
    std::cerr << "nav2_pyif_cycle_bench: " << error.what() << std::endl;
  }
  if (options.rclcpp) {
    rclcpp::shutdown();
  }
  return code;
}
