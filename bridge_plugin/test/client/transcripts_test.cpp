// The shared session transcripts (protocol/vectors/transcripts, PROTOCOL.md section 18),
// replayed by the plugin's sessions: each Nav2 call of a transcript must make exactly its
// requests, byte for byte, to its key and replica, waiting its timeout, and end as it says
// (a return value, or the nav2_core exception named). The reference client replays the same
// files (tests/test_transcripts.py).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fakes.hpp"
#include "nav2_pyif_bridge/client/behavior_session.hpp"
#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/client/planner_session.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;
using Json = nlohmann::ordered_json;

std::filesystem::path transcripts_dir() {return NAV2_PYIF_TRANSCRIPTS_DIR;}

std::vector<std::string> transcript_names()
{
  std::vector<std::string> names;
  for (const auto & entry : std::filesystem::directory_iterator(transcripts_dir())) {
    if (entry.path().extension() == ".json") {
      names.push_back(entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

Json load(const std::string & name)
{
  std::ifstream in(transcripts_dir() / (name + ".json"));
  return Json::parse(in);
}

std::string hex(const proto::Bytes & bytes)
{
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const std::uint8_t byte : bytes) {
    out += kHex[byte >> 4];
    out += kHex[byte & 0x0f];
  }
  return out;
}

proto::Bytes unhex(const std::string & text)
{
  proto::Bytes out;
  for (std::size_t i = 0; i + 1 < text.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(text.substr(i, 2), nullptr, 16)));
  }
  return out;
}

// The op, epoch and seq of an encoded request, for a failure's message.
std::string readable(const proto::Bytes & payload)
{
  try {
    const proto::Request request = proto::decode_request(payload);
    return std::string(proto::op_name(request.op())) + " epoch " +
           std::to_string(request.epoch) + " seq " + std::to_string(request.seq) + " " +
           hex(payload);
  } catch (const std::exception & error) {
    return std::string("<undecodable: ") + error.what() + ">";
  }
}

Duration seconds(const Json & value)
{
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(value.get<double>()));
}

// The hosts and their replies as the transcript has them: each query must be the next
// exchange expected; silence costs no time.
class ScriptedTransport : public Transport
{
public:
  explicit ScriptedTransport(FakeClock & clock)
  : watcher_(clock) {}

  std::optional<proto::Bytes> query(
    const Target & target, const proto::Bytes & payload, Duration timeout,
    const WaitHook *) override
  {
    if (expected.empty()) {
      ADD_FAILURE() << "a request the transcript does not have: " << readable(payload);
      return std::nullopt;
    }
    const Json exchange = expected.front();
    expected.pop_front();
    const std::string op = exchange["op"];
    EXPECT_EQ(target.key, exchange["key"].get<std::string>()) << op;
    EXPECT_EQ(target.host, exchange["host"].get<std::string>()) << op;
    EXPECT_EQ(timeout.count(), seconds(exchange["timeout_s"]).count())
      << op << " waits the wrong timeout; the transcript's class is " << exchange["timeout"];
    const std::string wanted = exchange["request"];
    EXPECT_EQ(hex(payload), wanted)
      << op << " differs:\n sent     " << readable(payload) << "\n expected "
      << readable(unhex(wanted));
    if (exchange["reply"].is_null()) {
      return std::nullopt;
    }
    return unhex(exchange["reply"].get<std::string>());
  }

  void send(const Target & target, const proto::Bytes & payload, Duration) override
  {
    ADD_FAILURE() << "a query to " << target.key << " the transcript does not have: "
                  << readable(payload);
  }

  HostWatcher & hosts() override {return watcher_;}

  // The hosts alive from now on: tokens of the others go, new ones appear.
  void set_hosts(const std::set<std::string> & alive)
  {
    for (const std::string & host : watcher_.alive()) {
      if (alive.count(host) == 0) {
        watcher_.on_token(host, false);
      }
    }
    for (const std::string & host : alive) {
      watcher_.on_token(host, true);
    }
  }

  std::deque<Json> expected;

private:
  HostWatcher watcher_;
};

void set_costmap(GridCostmap & costmap, const Json & plain)
{
  costmap.frame_id = plain["frame_id"];
  costmap.size_x = plain["size_x"];
  costmap.size_y = plain["size_y"];
  costmap.resolution = plain["resolution"];
  costmap.origin_x = plain["origin_x"];
  costmap.origin_y = plain["origin_y"];
  costmap.data = unhex(plain["data"]);
  costmap.footprint = plain["footprint"].get<std::vector<double>>();
  costmap.robot_radius = plain["robot_radius"];
}

proto::Params params_of(const Json & object)
{
  proto::Params params;
  for (const auto & [name, value] : object.items()) {
    if (value.is_boolean()) {
      params.set(name, value.get<bool>());
    } else if (value.is_number_integer()) {
      params.set(name, value.get<std::int64_t>());
    } else if (value.is_number_float()) {
      params.set(name, value.get<double>());
    } else {
      params.set(name, value.get<std::string>());
    }
  }
  return params;
}

proto::PoseStamped pose_of(const Json & wire)
{
  proto::PoseStamped pose;
  pose.frame_id = wire["frame_id"];
  pose.stamp_ns = wire["stamp_ns"];
  pose.pose = wire["pose"].get<std::array<double, 7>>();
  return pose;
}

proto::GoalChecker tolerances_of(const Json & wire)
{
  return proto::GoalChecker{
    wire["xy_goal_tolerance"], wire["yaw_goal_tolerance"], wire["trans_stopped_velocity"],
    wire["rot_stopped_velocity"], std::nullopt};
}

proto::Path path_of(const Json & wire)
{
  proto::Path path;
  path.frame_id = wire["frame_id"];
  path.stamp_ns = wire["stamp_ns"];
  for (const auto & row : wire["poses"]) {
    for (const auto & value : row) {
      path.poses.push_back(value.get<double>());
    }
  }
  return path;
}

// One transcript's plugin sessions on a ScriptedTransport.
class Replay
{
public:
  explicit Replay(const Json & transcript, const std::string & name)
  {
    set_costmap(costmap_, transcript["costmap"]);
    const Json & t = transcript["timeouts"];
    Timeouts timeouts;
    timeouts.call = seconds(t["call"]);
    timeouts.lifecycle = seconds(t["lifecycle"]);
    timeouts.configure = seconds(t["configure"]);
    timeouts.plan = seconds(t["plan"]);
    for (const Json & plugin : transcript["plugins"]) {
      SessionConfig config;
      config.key_prefix = plugin["key"];
      config.name = plugin["name"];
      config.node = plugin["node"];
      config.params = params_of(plugin["params"]);
      config.global_frame = plugin["global_frame"];
      config.robot_base_frame = plugin["robot_base_frame"];
      config.timeouts = timeouts;
      config.session_id = plugin["sid"];
      sessions_[plugin["id"]] = make(plugin["type"], config);
    }
    if (transcript["cycle"].get<bool>()) {
      cycle_ = CarriedCycle::of("/transcript_" + name);
      for (auto & [id, session] : sessions_) {
        session->join(cycle_);
      }
      cycle_->use_controller(as<ControllerSession>("controller"));
      cycle_->use_progress_checker(as<ProgressCheckerSession>("progress_checker"));
    }
  }

  void step(const Json & step)
  {
    if (step.contains("hosts")) {
      transport_.set_hosts(step["hosts"].get<std::set<std::string>>());
      return;
    }
    if (step.contains("costmap")) {
      set_costmap(costmap_, step["costmap"]);
      return;
    }
    const std::string where = step["plugin"].get<std::string>() + "." +
      step["call"].get<std::string>();
    SCOPED_TRACE(where);
    for (const Json & exchange : step["exchanges"]) {
      transport_.expected.push_back(exchange);
    }
    try {
      const Json returned = call(step);
      EXPECT_FALSE(step.contains("raises")) << "no exception; the transcript says "
                                            << step["raises"];
      if (step.contains("returns")) {
        EXPECT_EQ(returned, step["returns"]);
      }
    } catch (const CallError & error) {
      ASSERT_TRUE(step.contains("raises")) << "raised " << error.what();
      EXPECT_EQ(std::string(error_kind_name(error.kind())), step["raises"].get<std::string>())
        << error.what();
    }
    EXPECT_TRUE(transport_.expected.empty())
      << transport_.expected.size() << " request(s) of the transcript not sent, the first "
      << transport_.expected.front()["op"];
    transport_.expected.clear();
  }

private:
  std::unique_ptr<PluginSession> make(const std::string & type, const SessionConfig & config)
  {
    if (type == "controller") {
      return std::make_unique<ControllerSession>(config, transport_, costmap_);
    }
    if (type == "goal_checker") {
      return std::make_unique<GoalCheckerSession>(config, transport_, costmap_);
    }
    if (type == "progress_checker") {
      return std::make_unique<ProgressCheckerSession>(config, transport_, costmap_);
    }
    if (type == "costmap_layer") {
      return std::make_unique<CostmapLayerSession>(config, transport_, costmap_);
    }
    if (type == "global_planner") {
      return std::make_unique<PlannerSession>(config, transport_, costmap_);
    }
    if (type == "behavior") {
      return std::make_unique<BehaviorSession>(config, transport_, costmap_);
    }
    throw std::invalid_argument("a plugin type the replay does not know: " + type);
  }

  template<class Session>
  Session & as(const std::string & id)
  {
    auto * session = dynamic_cast<Session *>(sessions_.at(id).get());
    if (session == nullptr) {
      throw std::invalid_argument(id + " is not of the type the call needs");
    }
    return *session;
  }

  // Nav2's call; what it returned, as the transcript writes it (null for nothing).
  Json call(const Json & step)
  {
    const std::string id = step["plugin"];
    const std::string name = step["call"];
    const Json args = step.value("args", Json::object());
    PluginSession & session = *sessions_.at(id);
    if (name == "configure") {
      session.configure();
    } else if (name == "defer_configure") {
      session.defer_configure();
    } else if (name == "activate") {
      session.activate();
    } else if (name == "deactivate") {
      session.deactivate();
    } else if (name == "cleanup") {
      session.cleanup();
    } else if (name == "reset") {
      session.call(proto::ResetRequest{});  // every plugin type's: the op's timeout class
    } else if (name == "set_plan") {
      as<ControllerSession>(id).set_plan(path_of(args["path"]));
    } else if (name == "follow") {
      as<ControllerSession>(id).follow(path_of(args["path"]), pose_of(args["goal"]));
    } else if (name == "set_speed_limit") {
      as<ControllerSession>(id).set_speed_limit(args["speed_limit"], args["percentage"]);
    } else if (name == "compute_velocity_commands") {
      auto & controller = as<ControllerSession>(id);
      const auto pose = pose_of(args["pose"]);
      const auto velocity = args["velocity"].get<std::array<double, 6>>();
      const auto tolerances = tolerances_of(args["goal_checker"]);
      const proto::TwistStamped cmd = cycle_ ?
        cycle_->compute_velocity_commands(controller, pose, velocity, tolerances) :
        controller.compute_velocity_commands(pose, velocity, tolerances).cmd_vel;
      return cmd.twist;
    } else if (name == "is_goal_reached") {
      auto & checker = as<GoalCheckerSession>(id);
      const auto pose = pose_of(args["pose"]);
      const auto goal = args["goal"].get<std::array<double, 7>>();
      const auto velocity = args["velocity"].get<std::array<double, 6>>();
      const auto request = goal_check(pose.pose, goal, velocity);
      if (cycle_) {
        return cycle_->is_goal_reached(checker, pose, request, tolerances_of(args["tolerances"]));
      }
      return checker.call(request).reached;
    } else if (name == "check") {
      auto & checker = as<ProgressCheckerSession>(id);
      const auto request = progress_check(pose_of(args["pose"]));
      return cycle_ ? cycle_->check(checker, request) : checker.call(request).making_progress;
    } else if (name == "create_plan") {
      as<PlannerSession>(id).create_plan(
        plan_request(pose_of(args["start"]), pose_of(args["goal"])));
    } else if (name == "run") {
      return status_name(
        as<BehaviorSession>(id).run(args["action"], params_of(args["command"]),
        pose_of(args["pose"])));
    } else if (name == "cycle_update") {
      return status_name(
        as<BehaviorSession>(id).cycle_update(pose_of(args["pose"]), args["elapsed"]));
    } else if (name == "action_completion") {
      as<BehaviorSession>(id).action_completion(args["status"], args["elapsed"]);
    } else {
      ADD_FAILURE() << "a call the replay does not know: " << name;
    }
    return nullptr;
  }

  // A behaviour step's status as the wire names it (a failed call is a failed step).
  static std::string status_name(const BehaviorStep & step)
  {
    EXPECT_EQ(step.error, "") << "the behaviour's call failed";
    return std::string(protocol::kBehaviorStatusNames[static_cast<std::size_t>(step.status)]);
  }

  FakeClock clock_;
  ScriptedTransport transport_{clock_};
  GridCostmap costmap_;
  std::shared_ptr<CarriedCycle> cycle_;
  std::map<std::string, std::unique_ptr<PluginSession>> sessions_;
};

class TranscriptTest : public ::testing::TestWithParam<std::string> {};

TEST_P(TranscriptTest, ReplaysByteForByte)
{
  const Json transcript = load(GetParam());
  Replay replay(transcript, GetParam());
  for (const Json & step : transcript["steps"]) {
    replay.step(step);
    if (HasFatalFailure()) {
      return;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
  Transcripts, TranscriptTest, ::testing::ValuesIn(transcript_names()),
  [](const ::testing::TestParamInfo<std::string> & info) {return info.param;});

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
