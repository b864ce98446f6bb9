// The global planner's session against a fake host (tests/test_host_e2e.py's planner session
// and cancellation), with Nav2's cancel checker on the fake clock.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fakes.hpp"
#include "nav2_pyif_bridge/client/planner_session.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;
const char * const kKey = "nav2_pyif/test_robot/GridBased";

class PlannerSessionTest : public ::testing::Test
{
protected:
  PlannerSession & make()
  {
    SessionConfig config;
    config.key_prefix = kKey;
    config.name = "GridBased";
    config.node = "planner_server";
    config.params.set("points", std::int64_t{25});
    config.global_frame = "map";
    session = std::make_unique<PlannerSession>(config, host, costmap, log.logger());
    session->configure();
    session->activate();
    return *session;
  }

  void set_mode(const std::string & mode)
  {
    proto::Params p;
    p.set("mode", mode);
    session->set_parameters(p);
  }


  FakeClock clock;
  FakeHost host{clock};
  GridCostmap costmap;
  LogSink log;
  std::unique_ptr<PlannerSession> session;
};

TEST_F(PlannerSessionTest, PlansAndSendsTheCostmapOnce)
{
  auto & s = make();
  const auto configure = std::get<proto::ConfigureRequest>(host.received[0].request.body);
  EXPECT_EQ(configure.plugin_type, "global_planner");
  const proto::Path plan =
    s.create_plan(plan_request(pose_at(0, 0, "map"), pose_at(2.0, 1.0, "map")));
  EXPECT_EQ(plan.pose_count(), 25u);
  EXPECT_EQ(plan.poses[24 * 7], 2.0);
  EXPECT_EQ(plan.poses[24 * 7 + 1], 1.0);
  EXPECT_FALSE(host.last_had_costmap());  // configure delivered it
  costmap.resolution = 0.1;
  s.create_plan(plan_request(pose_at(0, 0, "map"), pose_at(1.0, 1.0, "map")));
  EXPECT_TRUE(host.last_had_costmap());
}

TEST_F(PlannerSessionTest, APlanWaitsForARestartingHostWithinItsTimeout)
{
  auto & s = make();
  host.kill();
  const Duration killed = clock.elapsed();
  clock.at(killed + 2s, [&] {host.start();});  // the host is back 2 s later
  const proto::Path plan =
    s.create_plan(plan_request(pose_at(0, 0, "map"), pose_at(2.0, 1.0, "map")));
  EXPECT_EQ(plan.pose_count(), 25u);
  EXPECT_EQ(clock.elapsed() - killed, Duration{2s});  // waited for it, not a recovery
  EXPECT_EQ(s.state().resyncs, 1u);

  host.kill();
  const Duration before = clock.elapsed();
  const CallError e = error_of([&] {s.create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)));});
  EXPECT_EQ(e.cause(), Cause::NoHost);
  EXPECT_EQ(clock.elapsed() - before, Duration{5s});  // no host came: the plan timeout
}

TEST_F(PlannerSessionTest, APlanWhoseHostDiesInTheCallIsSentAgainToItsRestart)
{
  auto & s = make();
  const std::string first = host.host_id();
  host.dies_during_next_call = 300ms;  // killed 300 ms into create_plan: Zenoh ends the query
  const Duration sent = clock.elapsed();
  clock.at(sent + 2s, [&] {host.start();});  // ... and the host is back 2 s after the call
  const proto::Path plan =
    s.create_plan(plan_request(pose_at(0, 0, "map"), pose_at(2.0, 1.0, "map")));
  EXPECT_EQ(plan.pose_count(), 25u);  // no recovery: the restarted host planned it
  EXPECT_EQ(clock.elapsed() - sent, Duration{2s});
  EXPECT_EQ(s.state().resyncs, 1u);  // the new host was given the session first
  EXPECT_EQ(host.received.back().answered_by, host.host_id());
  EXPECT_NE(host.host_id(), first);
  EXPECT_TRUE(log.contains(
      std::string(kKey) + ": host " + first + " went away during create_plan; sending it again"));

  // Where the host was the Zenoh session's only link, its death breaks the query at once
  // (a transport error), a moment before its token goes: the same wait, the same retry.
  host.transport_error_once = true;
  const std::string second = host.host_id();
  const Duration broken = clock.elapsed();
  clock.at(broken + 100ms, [&] {host.kill();});
  clock.at(broken + 1s, [&] {host.start();});
  EXPECT_EQ(s.create_plan(plan_request(pose_at(0, 0), pose_at(1, 1))).pose_count(), 25u);
  EXPECT_EQ(clock.elapsed() - broken, Duration{1s});
  EXPECT_EQ(s.state().resyncs, 2u);
  EXPECT_TRUE(log.contains(": host " + second + " went away during create_plan"));

  // No host back within the plan's timeout (5 s): the call fails as a dead host's, typed.
  host.dies_during_next_call = 300ms;
  const Duration before = clock.elapsed();
  const CallError e = error_of([&] {s.create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)));});
  EXPECT_EQ(e.cause(), Cause::TimedOut);
  EXPECT_EQ(e.kind(), ErrorKind::PlannerException);
  EXPECT_NE(std::string(e.what()).find("the query ended after 300 ms of 5000 (its host went away)"),
    std::string::npos) << e.what();
  EXPECT_EQ(clock.elapsed() - before, Duration{5s});
}

TEST_F(PlannerSessionTest, PlannerErrorsAreTyped)
{
  make();
  set_mode("occupied");
  const CallError e =
    error_of([&] {session->create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)));});
  EXPECT_EQ(e.kind(), ErrorKind::GoalOccupied);
  EXPECT_EQ(std::string(e.what()), "goal is in a wall");
  EXPECT_EQ(for_api(e.kind(), Nav2Api::Humble), ErrorKind::PlannerException);
}

TEST_F(PlannerSessionTest, CancellationIsForwardedOnceAndThePlannerAnswers)
{
  make();
  set_mode("slow");  // the planner would take 10 s
  const Duration cancel_at = clock.elapsed() + 200ms;
  int polls = 0;
  const Duration started = clock.elapsed();
  const std::size_t sent = host.received.size();
  const CallError e = error_of(
    [&] {
      session->create_plan(
        plan_request(pose_at(0, 0), pose_at(1, 1)),
        [&] {++polls; return clock.elapsed() > cancel_at;});
    });
  EXPECT_EQ(e.kind(), ErrorKind::PlannerCancelled);
  EXPECT_LT(clock.elapsed() - started, Duration{2s});  // cancelled, not the planner's 10 s
  EXPECT_GE(polls, 40);                                 // polled every 5 ms
  EXPECT_EQ(session->cancels_sent(), 1u);
  ASSERT_EQ(host.ops_since(sent), (std::vector<std::string>{"create_plan", "cancel_plan"}));
  const auto & sent_plan = host.received[sent].request;
  const auto & cancel = host.received[sent + 1];
  EXPECT_EQ(cancel.key, std::string(kKey) + "/cancel");
  EXPECT_EQ(std::get<proto::CancelPlanRequest>(cancel.request.body).target_seq, sent_plan.seq);
  EXPECT_GT(cancel.request.seq, sent_plan.seq);  // its own seq
  EXPECT_EQ(cancel.request.epoch, sent_plan.epoch);

  set_mode("ok");
  EXPECT_EQ(session->create_plan(plan_request(pose_at(0, 0), pose_at(3, 3))).pose_count(), 25u);
}

TEST_F(PlannerSessionTest, ACheckerThatNeverCancelsSendsNothing)
{
  make();
  host.next_call_time = 50ms;
  const auto plan =
    session->create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)), [] {return false;});
  EXPECT_EQ(plan.pose_count(), 25u);
  EXPECT_EQ(session->cancels_sent(), 0u);
}

TEST_F(PlannerSessionTest, TimeoutIsThePlannerExceptionNav2RecoversFrom)
{
  make();
  host.next_call_time = 6s;
  const CallError e =
    error_of([&] {session->create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)));});
  EXPECT_EQ(e.kind(), ErrorKind::PlannerException);
  EXPECT_EQ(e.cause(), Cause::TimedOut);
  EXPECT_EQ(
    std::string(e.what()), "create_plan got no reply from " + std::string(kKey) +
    " within 5000 ms");
}

TEST_F(PlannerSessionTest, NonFinitePlansNeverReachNav2)
{
  make();
  set_mode("nan");
  const CallError e =
    error_of([&] {session->create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)));});
  EXPECT_EQ(e.kind(), ErrorKind::NoValidPathCouldBeFound);
  EXPECT_NE(std::string(e.what()).find("pose 0"), std::string::npos) << e.what();
}

TEST_F(PlannerSessionTest, NoHostIsTheGenericPlannerException)
{
  make();
  host.kill();
  const CallError e =
    error_of([&] {session->create_plan(plan_request(pose_at(0, 0), pose_at(1, 1)));});
  EXPECT_EQ(e.kind(), ErrorKind::PlannerException);
  EXPECT_EQ(e.cause(), Cause::NoHost);
}

TEST_F(PlannerSessionTest, HostRestartReestablishes)
{
  make();
  host.restart();
  EXPECT_EQ(session->create_plan(plan_request(pose_at(0, 0), pose_at(1, 1))).pose_count(), 25u);
  EXPECT_EQ(session->state().resyncs, 1u);
  EXPECT_EQ(session->state().epoch, 2u);
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
