// The controller's session against a fake host: the C++ twin of tests/test_host_e2e.py
// (full session, costmap only when changed, host restart mid-session with the plan restored,
// fail fast, a hung call timing out, a reply of another seq, typed errors).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fakes.hpp"
#include "nav2_pyif_bridge/client/controller_session.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;
const char * const kKey = "nav2_pyif/test_robot/FollowPath";

class ControllerSessionTest : public ::testing::Test
{
protected:
  ControllerSession & make(proto::Params params = {}, Timeouts timeouts = generous())
  {
    SessionConfig config;
    config.key_prefix = kKey;
    config.name = "FollowPath";
    config.node = "controller_server";
    config.params = std::move(params);
    config.global_frame = "odom";
    config.timeouts = timeouts;
    session = std::make_unique<ControllerSession>(config, host, costmap, log.logger());
    return *session;
  }

  static Timeouts generous()
  {
    Timeouts t;
    t.call = 2s;
    return t;
  }

  proto::TwistStamped compute(const std::optional<proto::GoalChecker> & checker = std::nullopt)
  {
    return session->compute_velocity_commands(pose_at(1.0, 1.0), {}, checker).cmd_vel;
  }


  FakeClock clock;
  FakeHost host{clock};
  GridCostmap costmap;
  LogSink log;
  std::unique_ptr<ControllerSession> session;
};

TEST_F(ControllerSessionTest, ConfigureWarnsOfParametersThePlannerIgnores)
{
  proto::Params params;
  params.set("gain", 2.0);
  params.set("gian", 3.0);
  params.set("lable", std::string("x"));
  auto & s = make(params);
  s.configure();
  EXPECT_EQ(s.state().served, "fakes:Echo");
  EXPECT_TRUE(log.contains(
      std::string(kKey) + ": the planner ignores parameter(s) gian, lable: gian is not a "
      "parameter of this planner; lable is not a parameter of this planner; it declares: "
      "gain, label"));

  auto & quiet = make();  // every parameter known: nothing to warn of
  log.lines.clear();
  quiet.configure();
  EXPECT_FALSE(log.contains("ignores"));
}

TEST_F(ControllerSessionTest, FullSession)
{
  proto::Params params;
  params.set("gain", std::int64_t{2});
  auto & s = make(params);
  EXPECT_EQ(s.sid().size(), 32u);
  EXPECT_EQ(s.sid()[12], '4');  // UUID4

  const proto::Params declared = s.configure();
  ASSERT_EQ(declared.size(), 2u);
  EXPECT_EQ(std::get<double>(*declared.find("gain")), 2.0);
  EXPECT_EQ(std::get<std::string>(*declared.find("label")), "echo");
  EXPECT_NE(s.params().find("label"), nullptr);  // declared parameters join the session's
  s.activate();
  s.set_plan(straight_path(40, 3.0, 0.0));
  const auto cmd = compute(proto::GoalChecker{0.25, 0.3, 0.05, 0.1, std::nullopt});
  EXPECT_EQ(cmd.frame_id, "base_link");
  EXPECT_EQ(cmd.twist, (std::array<double, 6>{40.0, 2.0, -1.0, 1.0, 1.0, 1.0}));

  s.set_speed_limit(0.4, false);
  proto::Params changes;
  changes.set("gain", 5.0);
  changes.set("label", std::int64_t{3});
  const proto::StringMap rejected = s.set_parameters(changes);
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_EQ(*rejected.find("label"), "label: expected str, got int");
  EXPECT_EQ(std::get<double>(*s.params().find("gain")), 5.0);   // accepted: kept
  EXPECT_EQ(std::get<std::string>(*s.params().find("label")), "echo");  // refused: not kept

  const auto cmd2 = compute();
  EXPECT_EQ(cmd2.twist[1], 5.0);
  EXPECT_EQ(cmd2.twist[2], 0.4);
  EXPECT_EQ(cmd2.twist[4], 0.0);  // no goal checker this time
  EXPECT_TRUE(s.call(proto::CancelRequest{}).cancelled);
  s.call(proto::ResetRequest{});
  s.deactivate();
  s.cleanup();
  EXPECT_FALSE(s.state().configured);

  const std::size_t sent = host.received.size();
  const CallError e = error_of([&] {compute();});
  EXPECT_EQ(e.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(e.cause(), Cause::NotConfigured);
  EXPECT_EQ(std::string(e.what()), "compute_velocity_commands before configure on " + std::string(kKey));
  EXPECT_EQ(host.received.size(), sent);
  EXPECT_EQ(s.state().resyncs, 0u);

  EXPECT_EQ(
    host.ops(), (std::vector<std::string>{"configure", "activate", "set_plan",
      "compute_velocity_commands", "set_speed_limit", "set_parameters",
      "compute_velocity_commands", "cancel", "reset", "deactivate", "cleanup"}));
  std::uint64_t seq = 0;
  for (const auto & r : host.received) {
    EXPECT_EQ(r.request.sid, s.sid());
    EXPECT_EQ(r.request.epoch, 1u);
    EXPECT_GT(r.request.seq, seq);  // strictly increasing
    seq = r.request.seq;
  }
  const auto & configure = std::get<proto::ConfigureRequest>(host.received[0].request.body);
  EXPECT_EQ(configure.plugin_type, "controller");
  EXPECT_EQ(configure.name, "FollowPath");
  EXPECT_EQ(configure.node, "controller_server");
  EXPECT_EQ(configure.global_frame, "odom");
  EXPECT_EQ(configure.robot_base_frame, "base_link");
  EXPECT_EQ(configure.costmap.size_x, 40u);
  EXPECT_EQ(configure.costmap.data.size(), 1600u);
  EXPECT_EQ(std::get<std::int64_t>(*configure.params.find("gain")), 2);
}

TEST_F(ControllerSessionTest, CostmapTravelsOnlyWhenChanged)
{
  auto & s = make();
  s.configure();  // carries version 1
  EXPECT_EQ(s.state().delivered_costmap, 1u);
  s.activate();
  std::vector<bool> sent;
  std::vector<double> seen;
  int current = 1;
  for (const int version : {1, 1, 2, 2, 3}) {
    if (version != current) {
      costmap.data[static_cast<std::size_t>(version)] = 100;  // a cell changes
      current = version;
    }
    seen.push_back(compute().twist[3]);
    sent.push_back(host.last_had_costmap());
  }
  EXPECT_EQ(sent, (std::vector<bool>{false, false, true, false, true}));
  EXPECT_EQ(seen, (std::vector<double>{1, 1, 2, 2, 3}));  // the host sees the current version
  EXPECT_LT(host.received[3].bytes, 1600u);
  EXPECT_GT(host.received[4].bytes, 1600u);  // the 40 x 40 grid travels as bin
}

TEST_F(ControllerSessionTest, CostmapIsDeliveredOnlyByAnOkReply)
{
  auto & s = make();
  s.configure();
  s.activate();
  costmap.origin_x = 1.0;
  host.error_once = proto::Error{"FailedToMakeProgress", "stuck", "", ""};
  EXPECT_THROW(compute(), CallError);
  EXPECT_TRUE(host.last_had_costmap());
  EXPECT_EQ(s.state().delivered_costmap, 1u);  // the failed call delivered nothing
  compute();
  EXPECT_TRUE(host.last_had_costmap());  // so it travels again
  EXPECT_EQ(s.state().delivered_costmap, 2u);
  compute();
  EXPECT_FALSE(host.last_had_costmap());
}

// Lyrical: controller_server hands the controller the plan it transformed, every cycle. The
// request carries the plan and the global goal only when they changed (their stamps aside),
// and a restarted host gets both again with set_plan.
TEST_F(ControllerSessionTest, FollowCarriesThePlanAndGoalOnlyWhenTheyChange)
{
  auto & s = make();
  s.configure();
  s.activate();
  const auto body_of = [&](std::size_t i) {
      return std::get<proto::ComputeVelocityCommandsRequest>(host.received.at(i).request.body);
    };
  proto::Path plan = straight_path(12, 2.0, 0.0);
  proto::PoseStamped goal = pose_at(2.0, 0.0);
  s.follow(plan, goal);
  // the goal check cannot carry a command: Nav2 transforms the cycle's plan after it
  EXPECT_FALSE(s.prepare_command(pose_at(1.0, 1.0), {}, std::nullopt).has_value());
  EXPECT_EQ(compute().twist[0], 12.0);  // the host's set_plan saw the carried plan
  const std::size_t first = host.received.size() - 1;
  ASSERT_TRUE(body_of(first).plan.has_value());
  EXPECT_EQ(body_of(first).plan->pose_count(), 12u);
  ASSERT_TRUE(body_of(first).goal.has_value());
  EXPECT_EQ(body_of(first).goal->pose, goal.pose);

  plan.stamp_ns += 50'000'000;  // the next cycle: stamped anew, the same poses
  goal.stamp_ns += 50'000'000;
  s.follow(plan, goal);
  compute();
  EXPECT_FALSE(body_of(host.received.size() - 1).plan.has_value());
  EXPECT_FALSE(body_of(host.received.size() - 1).goal.has_value());

  proto::Path pruned = straight_path(9, 2.0, 0.0);  // the robot moved on: pruned
  s.follow(pruned, goal);
  EXPECT_EQ(compute().twist[0], 9.0);
  ASSERT_TRUE(body_of(host.received.size() - 1).plan.has_value());
  EXPECT_FALSE(body_of(host.received.size() - 1).goal.has_value());  // the goal did not move

  host.restart();
  const std::size_t sent = host.received.size();
  s.follow(pruned, goal);
  EXPECT_EQ(compute().twist[0], 9.0);  // restored with set_plan
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"compute_velocity_commands", "configure",
      "activate", "set_plan", "compute_velocity_commands"}));
  const auto & restored = std::get<proto::SetPlanRequest>(host.received.at(sent + 3).request.body);
  EXPECT_EQ(restored.path.pose_count(), 9u);
  ASSERT_TRUE(restored.goal.has_value());
  EXPECT_EQ(restored.goal->pose, goal.pose);
}

TEST_F(ControllerSessionTest, HostRestartMidSessionRestoresThePlan)
{
  proto::Params params;
  params.set("gain", 4.0);
  auto & s = make(params);
  s.configure();
  s.activate();
  s.set_plan(straight_path(17, 1.0, 0.0));
  s.set_speed_limit(30.0, true);
  proto::Params changes;
  changes.set("gain", 6.0);
  s.set_parameters(changes);
  EXPECT_EQ(compute().twist[0], 17.0);

  host.kill();  // SIGKILL: nothing is saved by the host
  const std::size_t sent = host.received.size();
  const Duration before = clock.elapsed();
  const CallError dead = error_of([&] {compute();});
  EXPECT_EQ(dead.kind(), ErrorKind::NoValidControl);  // Nav2 recovers from it
  EXPECT_EQ(dead.cause(), Cause::NoHost);
  EXPECT_NE(std::string(dead.what()).find("no planner host is alive"), std::string::npos);
  EXPECT_EQ(host.received.size(), sent);  // nothing sent ...
  EXPECT_EQ(clock.elapsed(), before);     // ... and no timeout waited

  host.start();
  costmap.data[0] = 7;  // the costmap changed meanwhile
  const auto cmd = compute();
  EXPECT_EQ(cmd.twist[0], 17.0);  // plan restored
  EXPECT_EQ(cmd.twist[1], 6.0);   // parameter change restored
  EXPECT_EQ(cmd.twist[2], 30.0);  // speed limit restored
  EXPECT_EQ(cmd.twist[3], 2.0);   // the current costmap
  EXPECT_EQ(s.state().resyncs, 1u);
  EXPECT_EQ(s.state().epoch, 2u);
  EXPECT_TRUE(log.contains("does not know session " + s.sid().substr(0, 8)));

  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"compute_velocity_commands", "configure",
      "activate", "set_plan", "set_speed_limit", "compute_velocity_commands"}));
  const auto & failed = host.received[sent];
  EXPECT_EQ(failed.request.epoch, 1u);
  const auto & configure = std::get<proto::ConfigureRequest>(host.received[sent + 1].request.body);
  EXPECT_EQ(host.received[sent + 1].request.epoch, 2u);
  EXPECT_EQ(std::get<double>(*configure.params.find("gain")), 6.0);
  EXPECT_EQ(configure.costmap.version, 2u);  // the full, current costmap
  const auto & retry = host.received.back().request;
  EXPECT_EQ(retry.epoch, 2u);
  EXPECT_FALSE(std::get<proto::ComputeVelocityCommandsRequest>(retry.body).costmap);  // delivered
  EXPECT_GT(retry.seq, failed.request.seq);
}

TEST_F(ControllerSessionTest, NoHostFailsFast)
{
  host.kill();
  Timeouts t;
  t.configure = 5s;
  auto & s = make({}, t);
  const CallError e = error_of([&] {s.configure();});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_TRUE(e.unreachable());
  EXPECT_EQ(
    std::string(e.what()), "no planner host is alive on " + std::string(kKey) +
    " (start one: planner-host --key " + kKey + " ...); configure not sent");
  EXPECT_TRUE(host.received.empty());
  EXPECT_EQ(clock.elapsed(), Duration{0});  // no 5 s timeout wait
}

TEST_F(ControllerSessionTest, AHungCallTimesOutAndTheNextCallWorks)
{
  Timeouts t;
  t.call = 300ms;
  auto & s = make({}, t);
  s.configure();
  s.activate();
  host.next_call_time = 1s;
  const Duration before = clock.elapsed();
  const CallError e = error_of([&] {compute();});
  // NoValidControl, not ControllerTimedOut: Jazzy's BT recovers from the one and ends the
  // navigation on the other, and controller_server's failure_tolerance retries only it.
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_EQ(e.cause(), Cause::TimedOut);
  EXPECT_EQ(
    std::string(e.what()),
    "compute_velocity_commands got no reply from " + std::string(kKey) + " within 300 ms");
  EXPECT_EQ(clock.elapsed() - before, Duration{300ms});  // the op's timeout, not the host's 1 s
  EXPECT_TRUE(std::isfinite(compute().twist[0]));
}

TEST_F(ControllerSessionTest, EachOpUsesItsTimeout)
{
  Timeouts t;
  t.call = 40ms;
  t.lifecycle = 2s;
  t.configure = 9s;
  auto & s = make({}, t);
  host.call_time = 100s;
  auto waited = [&](auto && f) {
      const Duration before = clock.elapsed();
      EXPECT_THROW(f(), CallError);
      return clock.elapsed() - before;
    };
  EXPECT_EQ(waited([&] {s.configure();}), Duration{9s});
  s.defer_configure();
  host.call_time = 0s;
  s.configure();
  host.call_time = 100s;
  Duration before = clock.elapsed();
  s.activate();  // no reply: applied when the session is re-established
  EXPECT_EQ(clock.elapsed() - before, Duration{2s});
  host.call_time = 0s;
  s.set_plan(straight_path(2, 1, 0));  // re-establishes: configure, activate, set_plan
  host.call_time = 100s;
  EXPECT_EQ(
    waited(
      [&] {
        if (auto deferred = s.set_plan(straight_path(2, 1, 0))) {
          throw *deferred;  // kept as owed, not thrown: the 40 ms is what is measured
        }
      }), Duration{40ms});
  EXPECT_EQ(waited([&] {s.set_speed_limit(1.0, false);}), Duration{40ms});
  EXPECT_EQ(waited([&] {compute();}), Duration{40ms});
  EXPECT_EQ(waited([&] {s.call(proto::CancelRequest{}).cancelled;}), Duration{40ms});
  EXPECT_EQ(waited([&] {s.call(proto::ResetRequest{});}), Duration{40ms});  // Nav2 resets after every goal
  EXPECT_EQ(waited([&] {s.set_parameters(proto::Params{});}), Duration{2s});
}

TEST_F(ControllerSessionTest, AReplyOfAnotherSeqIsAnError)
{
  auto & s = make();
  s.configure();
  host.seq_offset_once = 1;
  const CallError e = error_of([&] {s.activate();});
  EXPECT_EQ(e.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(e.cause(), Cause::BadReply);
  const std::uint64_t seq = host.last().seq;
  EXPECT_EQ(
    std::string(e.what()), "reply to activate has seq " + std::to_string(seq + 1) +
    ", expected " + std::to_string(seq));
  EXPECT_FALSE(s.state().active);
  s.activate();
  EXPECT_TRUE(s.state().active);
}

TEST_F(ControllerSessionTest, AReplyThatDoesNotDecodeIsAnError)
{
  auto & s = make();
  s.configure();
  host.raw_reply_once = proto::Bytes{0x81, 0xa1, 'v', 0x02};  // {"v": 2}
  const CallError e = error_of([&] {s.activate();});
  EXPECT_EQ(e.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(e.cause(), Cause::BadReply);
  EXPECT_EQ(std::string(e.what()).rfind("bad reply to activate: ", 0), 0u) << e.what();
}

TEST_F(ControllerSessionTest, ASecondSessionUnknownFailsTheCall)
{
  auto & s = make();
  s.configure();
  host.always_session_unknown = true;
  const CallError e = error_of([&] {s.activate();});
  EXPECT_EQ(e.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(e.remote().type, "SessionUnknown");
  EXPECT_EQ(std::string(e.what()).rfind("[SessionUnknown] ", 0), 0u);
  EXPECT_EQ(s.state().resyncs, 1u);
  EXPECT_EQ(host.ops(), (std::vector<std::string>{"configure", "activate", "configure", "activate"}));
}

TEST_F(ControllerSessionTest, ErrorsCrossTheWireTyped)
{
  auto & s = make();
  s.configure();
  s.activate();
  host.error_once = proto::Error{
    "FailedToMakeProgress", "FailedToMakeProgress raised on purpose",
    "Traceback (most recent call last):\n  in compute_velocity_commands\n", "nav2_pyif.FailedToMakeProgress"};
  const CallError named = error_of([&] {compute();});
  EXPECT_EQ(named.kind(), ErrorKind::FailedToMakeProgress);
  EXPECT_EQ(std::string(named.what()), "FailedToMakeProgress raised on purpose");
  EXPECT_NE(named.log_text().find("in compute_velocity_commands"), std::string::npos);

  host.error_once = proto::Error{"ControllerException", "ZeroDivisionError: division by zero",
    "Traceback ...\n    return 1 / 0\n", "builtins.ZeroDivisionError"};
  const CallError generic = error_of([&] {compute();});
  EXPECT_EQ(generic.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(generic.remote().python_type, "builtins.ZeroDivisionError");
  EXPECT_NE(generic.log_text().find("return 1 / 0"), std::string::npos);

  host.error_once = proto::Error{"GoalOccupied", "a planner's error", "", ""};
  const CallError other_kind = error_of([&] {compute();});
  EXPECT_EQ(other_kind.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(std::string(other_kind.what()), "[GoalOccupied] a planner's error");

  host.error_once = proto::Error{"Unavailable", "killed by signal SIGSEGV", "", ""};
  EXPECT_EQ(error_of([&] {compute();}).kind(), ErrorKind::NoValidControl);  // Nav2 recovers

  EXPECT_TRUE(std::isfinite(compute().twist[1]));  // the next call works
}

TEST_F(ControllerSessionTest, NonFiniteCommandsNeverReachNav2)
{
  auto & s = make();
  s.configure();
  s.activate();
  host.nan_once = true;
  const CallError e = error_of([&] {compute();});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_NE(std::string(e.what()).find("vx=nan"), std::string::npos) << e.what();
  EXPECT_TRUE(std::isfinite(compute().twist[0]));
}

TEST_F(ControllerSessionTest, DeferredConfigureEstablishesAtTheFirstCall)
{
  host.kill();
  auto & s = make();
  EXPECT_THROW(s.configure(), CallError);
  s.defer_configure();  // what the plugin does when no host is there at bring-up
  s.activate();         // local only: no host yet
  EXPECT_TRUE(s.state().active);
  proto::Params changes;
  changes.set("gain", 3.0);
  EXPECT_TRUE(s.set_parameters(changes).empty());  // kept for configure
  EXPECT_TRUE(host.received.empty());
  // still no host: fail fast, the plan kept as owed
  EXPECT_TRUE(s.set_plan(straight_path(5, 1, 0)).has_value());
  EXPECT_TRUE(host.received.empty());

  host.start();
  s.set_plan(straight_path(5, 1, 0));
  EXPECT_EQ(host.ops(), (std::vector<std::string>{"configure", "activate", "set_plan"}));
  const auto & configure = std::get<proto::ConfigureRequest>(host.received[0].request.body);
  EXPECT_EQ(std::get<double>(*configure.params.find("gain")), 3.0);
  EXPECT_EQ(compute().twist[0], 5.0);
  EXPECT_EQ(s.state().resyncs, 0u);
  EXPECT_TRUE(s.state().established);
}

TEST_F(ControllerSessionTest, ActivateEstablishesADeferredSessionWhenAHostAppeared)
{
  host.kill();
  auto & s = make();
  s.defer_configure();
  host.start();
  s.activate();
  EXPECT_EQ(host.ops(), (std::vector<std::string>{"configure", "activate"}));
  EXPECT_TRUE(s.state().established);
}

TEST_F(ControllerSessionTest, AFailedReestablishmentIsRetriedByTheNextCall)
{
  auto & s = make();
  s.configure();
  s.activate();
  s.set_plan(straight_path(9, 1, 0));
  Timeouts t = s.timeouts();
  t.configure = 1s;
  s.set_timeouts(t);
  host.restart();
  std::size_t sent = host.received.size();
  host.next_call_time = 0s;  // SessionUnknown at once ...
  host.call_time = 2s;       // ... then a configure slower than its timeout
  const CallError e = error_of([&] {compute();});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"compute_velocity_commands", "configure"}));
  EXPECT_TRUE(s.state().configured);  // not "before configure" from now on
  EXPECT_FALSE(s.state().established);

  host.call_time = 0s;
  sent = host.received.size();
  EXPECT_EQ(compute().twist[0], 9.0);  // established now, plan restored
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"configure", "activate", "set_plan",
      "compute_velocity_commands"}));
  EXPECT_EQ(s.state().epoch, 3u);
}

TEST_F(ControllerSessionTest, LifecycleTransitionsWithoutAHostAreAppliedLater)
{
  auto & s = make();
  s.configure();
  host.kill();
  EXPECT_NO_THROW(s.activate());  // Nav2's activation does not fail for a missing host
  EXPECT_TRUE(s.state().active);
  EXPECT_FALSE(s.state().established);
  host.start();
  const std::size_t sent = host.received.size();
  compute();
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"configure", "activate",
      "compute_velocity_commands"}));
  host.kill();
  EXPECT_NO_THROW(s.deactivate());
  EXPECT_FALSE(s.state().active);
  host.start();
  s.set_plan(straight_path(2, 1, 0));
  EXPECT_EQ(host.ops_since(sent + 3), (std::vector<std::string>{"configure", "set_plan"}));
}

TEST_F(ControllerSessionTest, ASpeedLimitSetWhileNoHostIsAliveReachesTheNextHost)
{
  auto & s = make();
  s.configure();
  s.activate();
  s.set_speed_limit(0.5, false);
  host.kill();
  EXPECT_THROW(s.set_speed_limit(0.2, false), CallError);  // a slow zone, no host
  host.start();
  EXPECT_EQ(compute().twist[2], 0.2);
}

TEST_F(ControllerSessionTest, APlanTheHostFailedIsKeptAndSentFirstNotThrown)
{
  auto & s = make();
  s.configure();
  s.activate();
  s.set_plan(straight_path(9, 1, 0));
  host.transport_error_once = true;  // the BT's replan while the host is unreachable
  const std::optional<CallError> deferred = s.set_plan(straight_path(12, 1, 0));
  ASSERT_TRUE(deferred.has_value());
  EXPECT_TRUE(deferred->host_failed());
  EXPECT_EQ(deferred->kind(), ErrorKind::NoValidControl);
  const std::size_t sent = host.received.size();
  EXPECT_EQ(compute().twist[0], 12.0);
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"set_plan", "compute_velocity_commands"}));
  EXPECT_EQ(compute().twist[0], 12.0);  // owed once
  EXPECT_EQ(host.ops_since(sent + 2), (std::vector<std::string>{"compute_velocity_commands"}));
  host.kill();
  EXPECT_TRUE(s.set_plan(straight_path(5, 1, 0)).has_value());  // no host: not thrown either
  host.start();
  EXPECT_EQ(compute().twist[0], 5.0);
}

TEST_F(ControllerSessionTest, ABrokenTransportIsUnreachableNotAPlannerError)
{
  auto & s = make();
  s.configure();
  s.activate();
  host.transport_error_once = true;
  const CallError e = error_of([&] {compute();});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_EQ(e.cause(), Cause::Transport);
  EXPECT_TRUE(e.unreachable());
  EXPECT_NE(std::string(e.what()).find("Zenoh query failed"), std::string::npos);
  host.transport_error_once = true;
  EXPECT_NO_THROW(s.deactivate());  // Nav2's deactivation goes on
  EXPECT_FALSE(s.state().active);
}

TEST_F(ControllerSessionTest, ResetWaitsTheCallTimeout)
{
  auto & s = make();
  s.configure();
  host.next_call_time = 10s;
  const Duration before = clock.elapsed();
  EXPECT_THROW(s.call(proto::ResetRequest{}), CallError);
  EXPECT_EQ(clock.elapsed() - before, s.timeouts().call);  // not the 5 s lifecycle timeout
  EXPECT_LT(s.timeouts().call, s.timeouts().lifecycle);
}

TEST_F(ControllerSessionTest, CleanupForgetsTheStateAndEndsTheSession)
{
  auto & s = make();
  s.configure();
  s.activate();
  s.set_plan(straight_path(3, 1, 0));
  EXPECT_TRUE(s.has_plan());
  host.kill();
  EXPECT_THROW(s.cleanup(), CallError);  // no host: the call fails ...
  EXPECT_FALSE(s.state().configured);           // ... the session ends anyway
  EXPECT_FALSE(s.state().active);
  EXPECT_FALSE(s.has_plan());
}

TEST_F(ControllerSessionTest, EncodingFailuresAreGenericErrorsAndNothingIsSent)
{
  auto & s = make();
  s.configure();
  proto::Path bad;
  bad.frame_id = "odom";
  bad.poses = {1.0, 2.0};  // not a whole pose
  const CallError e = error_of([&] {s.set_plan(bad);});
  EXPECT_EQ(e.kind(), ErrorKind::ControllerException);
  EXPECT_EQ(e.cause(), Cause::Local);
  EXPECT_EQ(host.ops(), (std::vector<std::string>{"configure"}));
}

// --- replicas (tests/test_replicas.py) ------------------------------------------------------

TEST_F(ControllerSessionTest, QueriesGoToThePinnedReplica)
{
  host.add_replica("a-replica");  // smaller than fake-host-1
  auto & s = make();
  s.configure();
  s.activate();
  EXPECT_EQ(s.state().pinned_host, "a-replica");
  for (const auto & r : host.received) {
    EXPECT_EQ(r.host, "a-replica");
    EXPECT_EQ(r.answered_by, "a-replica");
  }
  EXPECT_TRUE(host.has_session("a-replica", s.sid()));
  EXPECT_FALSE(host.has_session(host.host_id(), s.sid()));  // the other one ran nothing
  EXPECT_EQ(Target({"k/rpc/activate", "a-replica"}).parameters(), "host=a-replica");
  EXPECT_EQ(Target({"k/rpc/activate", ""}).parameters(), "");
}

TEST_F(ControllerSessionTest, AGoneTokenMovesThePinBeforeTheCall)
{
  host.add_replica("a-replica");
  auto & s = make();
  s.configure();
  s.activate();
  host.kill_replica("a-replica");
  const std::size_t sent = host.received.size();
  EXPECT_TRUE(std::isfinite(compute().twist[0]));
  EXPECT_EQ(s.state().failovers, 1u);
  EXPECT_TRUE(log.contains("host a-replica is gone; using " + host.host_id()));
  EXPECT_EQ(host.received[sent].host, host.host_id());  // no query to the dead one
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"compute_velocity_commands", "configure",
      "activate", "compute_velocity_commands"}));
}

TEST_F(ControllerSessionTest, UnavailableFailsOverWhenAnotherReplicaIsAlive)
{
  host.add_replica("a-replica");
  auto & s = make();
  s.configure();
  s.activate();
  host.error_once = proto::Error{"Unavailable", "worker restarting", "", ""};
  EXPECT_TRUE(std::isfinite(compute().twist[0]));
  EXPECT_EQ(s.state().pinned_host, host.host_id());
  EXPECT_EQ(s.state().failovers, 1u);
}

TEST_F(ControllerSessionTest, UnavailableWithoutAReplicaFails)
{
  auto & s = make();
  s.configure();
  host.error_once = proto::Error{"Unavailable", "worker restarting", "", ""};
  const CallError e = error_of([&] {s.activate();});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);  // a host failure: Nav2 recovers from it
  EXPECT_EQ(std::string(e.what()), "[Unavailable] worker restarting");
  EXPECT_EQ(s.state().failovers, 0u);
}

TEST_F(ControllerSessionTest, AFailoverRetriesOnlyOnce)
{
  host.add_replica("a-replica");
  Timeouts t = generous();
  t.call = 100ms;
  auto & s = make({}, t);
  s.configure();
  s.activate();
  host.freeze_replica("a-replica");
  host.freeze_replica(host.host_id());
  const CallError e = error_of([&] {compute();});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_EQ(s.state().failovers, 1u);
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
