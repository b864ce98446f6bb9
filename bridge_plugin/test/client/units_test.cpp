// The small units: error mapping, costmap versions, command checks, keys, the host watcher.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "fakes.hpp"
#include "nav2_pyif_bridge/client/command_check.hpp"
#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;

// --- ErrorMapping ---------------------------------------------------------------------------

const std::vector<std::string> kControllerNames = {
  "ControllerException", "InvalidController", "ControllerTFError", "FailedToMakeProgress",
  "PatienceExceeded", "InvalidPath", "NoValidControl", "ControllerTimedOut"};
const std::vector<std::string> kPlannerNames = {
  "PlannerException", "InvalidPlanner", "StartOccupied", "GoalOccupied",
  "StartOutsideMapBounds", "GoalOutsideMapBounds", "NoValidPathCouldBeFound",
  "PlannerTimedOut", "PlannerTFError", "NoViapointsGiven", "PlannerCancelled"};
const std::vector<std::string> kSmootherNames = {
  "SmootherException", "InvalidSmoother", "SmootherTimedOut", "SmoothedPathInCollision",
  "FailedToSmoothPath"};

proto::Error remote(const std::string & type)
{
  return proto::Error{type, "msg", "Traceback (most recent call last):\n  x\n", "pkg.Err"};
}

TEST(ErrorMapping, EveryNameOfThePluginsKindIsThrownAsItself)
{
  for (const auto & name : kControllerNames) {
    const CallError e = error_from_reply(remote(name), PluginKind::Controller);
    EXPECT_EQ(error_kind_name(e.kind()), name);
    EXPECT_EQ(std::string(e.what()), "msg");
    EXPECT_EQ(e.cause(), Cause::Remote);
    EXPECT_EQ(plugin_kind_of(e.kind()), PluginKind::Controller);
  }
  for (const auto & name : kPlannerNames) {
    const CallError e = error_from_reply(remote(name), PluginKind::GlobalPlanner);
    EXPECT_EQ(error_kind_name(e.kind()), name);
    EXPECT_EQ(plugin_kind_of(e.kind()), PluginKind::GlobalPlanner);
  }
  for (const auto & name : kSmootherNames) {
    const CallError e = error_from_reply(remote(name), PluginKind::Smoother);
    EXPECT_EQ(error_kind_name(e.kind()), name);
    EXPECT_EQ(plugin_kind_of(e.kind()), PluginKind::Smoother);
  }
  EXPECT_EQ(
    kControllerNames.size() + kPlannerNames.size() + kSmootherNames.size(), kErrorKindCount);
}

TEST(ErrorMapping, InvalidPathIsTheSmoothersTooAndCheckersOnlyThrowControllerException)
{
  // nav2_core has an InvalidPath among the smoother exceptions as well: the plugin's kind
  // picks the C++ class (nav2_exceptions.hpp).
  EXPECT_EQ(error_from_reply(remote("InvalidPath"), PluginKind::Smoother).kind(),
    ErrorKind::InvalidPath);
  for (const auto & name : kControllerNames) {
    if (name != "InvalidPath") {
      EXPECT_EQ(error_from_reply(remote(name), PluginKind::Smoother).kind(),
        ErrorKind::SmootherException) << name;
    }
  }
  for (const auto kind : {PluginKind::GoalChecker, PluginKind::ProgressChecker}) {
    EXPECT_EQ(error_from_reply(remote("ControllerException"), kind).kind(),
      ErrorKind::ControllerException);
    const CallError e = error_from_reply(remote("NoValidControl"), kind);
    EXPECT_EQ(e.kind(), ErrorKind::ControllerException);
    EXPECT_EQ(std::string(e.what()), "[NoValidControl] msg");
    EXPECT_EQ(host_failure_error(kind), ErrorKind::ControllerException);
    EXPECT_EQ(invalid_error(kind), ErrorKind::ControllerException);
  }
  EXPECT_EQ(generic_error(PluginKind::Smoother), ErrorKind::SmootherException);
  EXPECT_EQ(host_failure_error(PluginKind::Smoother), ErrorKind::SmootherException);
  EXPECT_EQ(invalid_error(PluginKind::Smoother), ErrorKind::InvalidSmoother);
  EXPECT_EQ(plugin_type_name(PluginKind::Smoother), "smoother");
  EXPECT_EQ(plugin_type_name(PluginKind::GoalChecker), "goal_checker");
  EXPECT_EQ(plugin_type_name(PluginKind::ProgressChecker), "progress_checker");
}

TEST(ErrorMapping, TheOtherKindsNamesAndProtocolErrorsAreGeneric)
{
  for (const auto & name : kPlannerNames) {
    const CallError e = error_from_reply(remote(name), PluginKind::Controller);
    EXPECT_EQ(e.kind(), ErrorKind::ControllerException) << name;
    EXPECT_EQ(std::string(e.what()), "[" + name + "] msg");
    EXPECT_EQ(e.remote().type, name);
  }
  for (const auto & name : kControllerNames) {
    EXPECT_EQ(
      error_from_reply(remote(name), PluginKind::GlobalPlanner).kind(),
      ErrorKind::PlannerException) << name;
  }
  for (const std::string name : {"SessionUnknown", "VersionMismatch", "BadRequest",
      "SomethingNew"})
  {
    EXPECT_EQ(error_from_reply(remote(name), PluginKind::Controller).kind(),
      ErrorKind::ControllerException);
    EXPECT_EQ(error_from_reply(remote(name), PluginKind::GlobalPlanner).kind(),
      ErrorKind::PlannerException);
  }
}

TEST(ErrorMapping, UnavailableIsAHostFailureThatNav2RecoversFrom)
{
  // A crashed, restarting or overrunning worker: NoValidControl for a controller (Jazzy+'s
  // WouldAControllerRecoveryHelp retries it; ControllerTimedOut would end the navigation).
  const CallError e = error_from_reply(remote("Unavailable"), PluginKind::Controller);
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_EQ(std::string(e.what()), "[Unavailable] msg");
  EXPECT_EQ(error_from_reply(remote("Unavailable"), PluginKind::GlobalPlanner).kind(),
    ErrorKind::PlannerException);
  EXPECT_EQ(error_from_reply(remote("Unavailable"), PluginKind::Smoother).kind(),
    ErrorKind::SmootherException);
  // A planner's own typed errors are kept as raised: a ControllerTimedOut means it.
  EXPECT_EQ(error_from_reply(remote("ControllerTimedOut"), PluginKind::Controller).kind(),
    ErrorKind::ControllerTimedOut);
}

TEST(ErrorMapping, HumbleThrowsPlannerExceptionForEverything)
{
  for (std::size_t i = 0; i < kErrorKindCount; ++i) {
    const auto kind = static_cast<ErrorKind>(i);
    EXPECT_EQ(for_api(kind, Nav2Api::Humble), ErrorKind::PlannerException);
    EXPECT_EQ(for_api(kind, Nav2Api::Jazzy), kind);
    EXPECT_EQ(error_kind_from_name(error_kind_name(kind)), kind);
  }
  EXPECT_EQ(error_kind_from_name("SessionUnknown"), std::nullopt);
}

TEST(ErrorMapping, GenericAndHostFailurePerPluginType)
{
  EXPECT_EQ(generic_error(PluginKind::Controller), ErrorKind::ControllerException);
  EXPECT_EQ(generic_error(PluginKind::GlobalPlanner), ErrorKind::PlannerException);
  EXPECT_EQ(host_failure_error(PluginKind::Controller), ErrorKind::NoValidControl);
  EXPECT_EQ(host_failure_error(PluginKind::GlobalPlanner), ErrorKind::PlannerException);
  EXPECT_EQ(plugin_type_name(PluginKind::Controller), "controller");
  EXPECT_EQ(plugin_type_name(PluginKind::GlobalPlanner), "global_planner");
}

TEST(ErrorMapping, LogTextCarriesTheTraceback)
{
  const CallError e = error_from_reply(
    proto::Error{"ControllerException", "ZeroDivisionError: division by zero",
      "Traceback (most recent call last):\n    return 1 / 0\n", "builtins.ZeroDivisionError"},
    PluginKind::Controller);
  EXPECT_EQ(
    e.log_text(), "ZeroDivisionError: division by zero (builtins.ZeroDivisionError)\n"
    "Python traceback from the planner host:\nTraceback (most recent call last):\n"
    "    return 1 / 0");
  EXPECT_EQ(CallError(ErrorKind::NoValidControl, Cause::Local, "plain").log_text(), "plain");
}

// --- CostmapVersion -------------------------------------------------------------------------

TEST(CostmapVersion, BumpsOnEveryKindOfChangeOnly)
{
  GridCostmap grid(4, 3, 0.05);
  auto version = [&] {return grid.read(std::nullopt).version;};
  EXPECT_EQ(version(), 1u);
  EXPECT_EQ(version(), 1u);  // unchanged
  grid.data[11] = 9;
  EXPECT_EQ(version(), 2u);
  grid.data[11] = 9;         // the same value again
  EXPECT_EQ(version(), 2u);
  grid.origin_x = 0.5;
  EXPECT_EQ(version(), 3u);
  grid.origin_y = -0.5;
  EXPECT_EQ(version(), 4u);
  grid.resolution = 0.1;
  EXPECT_EQ(version(), 5u);
  grid.footprint.back() = 0.3;
  EXPECT_EQ(version(), 6u);
  grid.robot_radius = 0.2;
  EXPECT_EQ(version(), 7u);
  grid.frame_id = "map";
  EXPECT_EQ(version(), 8u);
  grid.size_x = 3;  // same cell count, another shape
  grid.size_y = 4;
  EXPECT_EQ(version(), 9u);
  grid.size_x = 6;
  grid.data.assign(24, 0);
  EXPECT_EQ(version(), 10u);
  EXPECT_EQ(version(), 10u);
}

TEST(CostmapVersion, CopiesOnlyWhatTheReaderLacks)
{
  GridCostmap grid(4, 3);
  const CostmapRead first = grid.read(std::nullopt);
  ASSERT_TRUE(first.costmap);
  EXPECT_EQ(first.costmap->version, 1u);
  EXPECT_EQ(first.costmap->data, grid.data);
  EXPECT_EQ(first.costmap->size_x, 4u);
  EXPECT_EQ(first.costmap->frame_id, "odom");
  EXPECT_EQ(first.costmap->footprint, grid.footprint);
  EXPECT_FALSE(grid.read(1u).costmap);     // the reader has version 1
  EXPECT_TRUE(grid.read(std::nullopt).costmap);
  grid.data[0] = 255;
  const CostmapRead changed = grid.read(1u);
  ASSERT_TRUE(changed.costmap);
  EXPECT_EQ(changed.version, 2u);
  EXPECT_EQ(changed.costmap->data[0], 255);
  EXPECT_FALSE(grid.read(2u).costmap);
}

TEST(CostmapVersion, EmptyCostmap)
{
  GridCostmap grid(0, 0);
  EXPECT_EQ(grid.read(std::nullopt).version, 1u);
  EXPECT_EQ(grid.read(std::nullopt).version, 1u);
}

TEST(CostmapVersion, CellsAreEncodedAsTheWireExpects)
{
  GridCostmap grid(4, 3);
  auto read = grid.read(std::nullopt);
  proto::Request request;
  request.sid = "s";
  proto::ComputeVelocityCommandsRequest body;
  body.costmap = *read.costmap;
  request.body = body;
  const auto decoded = proto::decode_request(proto::encode_request(request));
  const auto & sent = std::get<proto::ComputeVelocityCommandsRequest>(decoded.body);
  EXPECT_EQ(sent.costmap->data, grid.data);
}

// --- command checks -------------------------------------------------------------------------

TEST(CommandCheck, NeverAcceptsANonFiniteTwist)
{
  proto::TwistStamped cmd;
  cmd.twist = {0.3, 0.0, 0.0, 0.0, 0.0, 0.5};
  EXPECT_NO_THROW(check_command(cmd, "h"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 6; ++i) {
    for (const double bad : {nan, inf, -inf}) {
      proto::TwistStamped c = cmd;
      c.twist[i] = bad;
      try {
        check_command(c, "h");
        ADD_FAILURE() << "component " << i << " accepted";
      } catch (const CallError & e) {
        EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
      }
    }
  }
  cmd.twist[0] = nan;
  cmd.twist[5] = -inf;
  EXPECT_EQ(non_finite_components(cmd), "vx=nan, wz=-inf");
}

TEST(CommandCheck, PathsMustBeFinite)
{
  proto::Path path = straight_path(3, 1.0, 1.0);
  EXPECT_NO_THROW(check_path(path, "h"));
  path.poses[15] = std::numeric_limits<double>::quiet_NaN();  // pose 2
  try {
    check_path(path, "h");
    ADD_FAILURE();
  } catch (const CallError & e) {
    EXPECT_EQ(e.kind(), ErrorKind::NoValidPathCouldBeFound);
    EXPECT_EQ(std::string(e.what()), "create_plan reply from host h has a non-finite value in pose 2 of 3");
  }
}

// --- HostWatcher ----------------------------------------------------------------------------

TEST(HostWatcher, TracksTokens)
{
  FakeClock clock;
  std::vector<std::pair<std::string, bool>> seen;
  HostWatcher watcher(clock, [&](const std::string & id, bool alive) {seen.emplace_back(id, alive);});
  EXPECT_FALSE(watcher.any_alive());
  watcher.on_token("a", true);
  watcher.on_token("a", true);  // the same token twice: no change
  watcher.on_token("b", true);
  watcher.on_token("a", false);
  EXPECT_TRUE(watcher.any_alive());
  EXPECT_EQ(watcher.alive(), (HostWatcher::Hosts{"b"}));
  watcher.on_token("b", false);
  watcher.on_token("c", false);  // unknown: no change
  EXPECT_FALSE(watcher.any_alive());
  EXPECT_EQ(watcher.changes(), 4u);
  EXPECT_EQ(seen.size(), 4u);
}

TEST(HostWatcher, WaitTimesOutOnTheClock)
{
  FakeClock clock;
  HostWatcher watcher(clock);
  EXPECT_FALSE(watcher.wait_for_any(5s));
  EXPECT_EQ(clock.elapsed(), Duration{5s});
}

TEST(HostWatcher, WaitEndsWhenAHostAppears)
{
  FakeClock clock;
  HostWatcher watcher(clock);
  clock.at(2s, [&] {watcher.on_token("h", true);});
  EXPECT_TRUE(watcher.wait_for_any(15s));
  EXPECT_EQ(clock.elapsed(), Duration{2s});
  clock.at(3s, [&] {watcher.on_token("h", false);});
  EXPECT_TRUE(watcher.wait_until([](const HostWatcher::Hosts & h) {return h.empty();}, 10s));
  EXPECT_EQ(clock.elapsed(), Duration{3s});
}

TEST(HostWatcher, WakesARealWaiterFromAnotherThread)
{
  HostWatcher watcher;  // steady clock
  std::thread zenoh([&] {
      std::this_thread::sleep_for(20ms);
      watcher.on_token("h", true);
    });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(watcher.wait_for_any(10s));
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
  zenoh.join();
}

// --- The costmap rides in every request that has the field ------------------------------------

proto::SmoothRequest smooth_request(double max_time)
{
  proto::SmoothRequest request;
  request.path = straight_path(5, 1.0, 0.0);
  request.max_time = max_time;
  return request;
}

TEST(CostmapDelivery, AChangedCostmapRidesInTheSmoothersRequest)
{
  // smooth's costmap was left out of a hand-written list: smoother_server's costmap reached
  // the Python smoother only at configure.
  FakeClock clock;
  FakeHost host{clock};  // answers smooth with BadRequest: only the request matters here
  GridCostmap costmap;
  SessionConfig config;
  config.key_prefix = "nav2_pyif/test_robot/simple_smoother";
  config.name = "simple_smoother";
  SmootherSession session(config, host, costmap);
  session.configure();
  costmap.resolution = 0.1;
  error_of([&] {session.call(smooth_request(0.1));});
  const auto & smooth = std::get<proto::SmoothRequest>(host.last().body);
  ASSERT_TRUE(smooth.costmap.has_value());
  EXPECT_EQ(smooth.costmap->resolution, 0.1);
}

TEST(SmootherSessionTest, WaitsMaxTimeAndAGraceOrThePlanTimeoutWhenLonger)
{
  FakeClock clock;
  FakeHost host(clock);  // answers smooth with BadRequest: only the wait matters here
  GridCostmap costmap;
  SessionConfig config;
  config.key_prefix = "nav2_pyif/test_robot/simple_smoother";
  config.timeouts.plan = std::chrono::seconds(2);
  SmootherSession session(config, host, costmap);
  session.configure();
  error_of([&] {session.call(smooth_request(5.0));});
  EXPECT_EQ(host.received.back().timeout, Duration(std::chrono::seconds(6)));
  error_of([&] {session.call(smooth_request(0.5));});
  EXPECT_EQ(host.received.back().timeout, Duration(std::chrono::seconds(2)));
  EXPECT_EQ(session.timeouts().plan, Duration(std::chrono::seconds(2)));  // not changed
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test

namespace nav2_pyif_bridge::client::test
{
namespace
{

TEST(SessionId, IsAUuid4InHexAsPythonWritesIt)
{
  const std::string a = new_session_id();
  const std::string b = new_session_id();
  ASSERT_EQ(a.size(), 32u);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos) << a;
  EXPECT_EQ(a[12], '4') << a;  // the version nibble
  EXPECT_NE(std::string("89ab").find(a[16]), std::string::npos) << a;  // the RFC 4122 variant
  EXPECT_NE(a, b);
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
