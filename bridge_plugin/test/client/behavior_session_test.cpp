// The behaviour's session against a fake host (tests/test_behavior_host.py's client side):
// TimedBehavior's run / cycle / completion, every failure a FAILED step (never an exception
// into behavior_server), and the action under way given again to a restarted host.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "fakes.hpp"
#include "nav2_pyif_bridge/client/behavior_session.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;
const char * const kKey = "nav2_pyif/test_robot/backup";
const char * const kBackUp = "nav2_msgs/action/BackUp";

proto::Params backup(double target_x, double speed)
{
  proto::Params command;
  command.set("target_x", target_x);
  command.set("target_y", 0.0);
  command.set("target_z", 0.0);
  command.set("speed", speed);
  command.set("time_allowance", 10.0);
  command.set("disable_collision_checks", false);
  return command;
}

double number(const proto::Params & params, const std::string & name)
{
  const auto * value = params.find(name);
  if (!value) {
    ADD_FAILURE() << "no " << name;
    return std::numeric_limits<double>::quiet_NaN();
  }
  return std::holds_alternative<double>(*value) ? std::get<double>(*value) :
         static_cast<double>(std::get<std::int64_t>(*value));
}

class BehaviorSessionTest : public ::testing::Test
{
protected:
  BehaviorSession & make()
  {
    SessionConfig config;
    config.key_prefix = kKey;
    config.name = "backup";
    config.node = "behavior_server";
    config.global_frame = "odom";
    session = std::make_unique<BehaviorSession>(config, host, costmap, log.logger());
    session->configure();
    session->activate();
    return *session;
  }

  FakeClock clock;
  FakeHost host{clock};
  GridCostmap costmap;
  LogSink log;
  std::unique_ptr<BehaviorSession> session;
};

TEST_F(BehaviorSessionTest, RunsThenCyclesUntilSucceededAndSaysWhenTheActionEnded)
{
  auto & s = make();
  const auto configure = std::get<proto::ConfigureRequest>(host.received[0].request.body);
  EXPECT_EQ(configure.plugin_type, "behavior");
  const BehaviorStep started = s.run(kBackUp, backup(-0.3, 0.15), pose_at(2.0, 1.0));
  EXPECT_EQ(started.status, BehaviorStatus::Succeeded);
  EXPECT_EQ(started.failure, BehaviorFailure::None);
  EXPECT_TRUE(started.error.empty()) << started.error;
  const auto run = std::get<proto::OnRunRequest>(host.last().body);
  EXPECT_EQ(run.action, kBackUp);
  EXPECT_EQ(number(run.command, "target_x"), -0.3);
  EXPECT_TRUE(s.running());

  double x = 2.0;
  int cycles = 0;
  BehaviorStep step = s.cycle_update(pose_at(x, 1.0), 0.0);
  while (step.status == BehaviorStatus::Running && cycles < 100) {
    ASSERT_TRUE(step.cmd_vel.has_value());
    EXPECT_EQ(step.cmd_vel->twist[0], -0.1);
    x += step.cmd_vel->twist[0] * 0.1;  // 10 Hz
    step = s.cycle_update(pose_at(x, 1.0), 0.1 * ++cycles);
  }
  EXPECT_EQ(step.status, BehaviorStatus::Succeeded);
  EXPECT_FALSE(step.cmd_vel.has_value());
  EXPECT_GE(number(step.feedback, "distance_traveled"), 0.3 - 1e-9);
  EXPECT_NEAR(cycles, 30, 1);
  s.action_completion("succeeded", 3.0);
  EXPECT_EQ(host.ops().back(), "on_action_completion");
  EXPECT_EQ(std::get<proto::OnActionCompletionRequest>(host.last().body).status, "succeeded");
  EXPECT_FALSE(s.running());
}

TEST_F(BehaviorSessionTest, TheLocalCostmapTravelsOnlyWhenItChanged)
{
  auto & s = make();
  s.run(kBackUp, backup(-0.3, 0.15), pose_at(0, 0));
  EXPECT_FALSE(host.last_had_costmap());  // configure delivered it
  s.cycle_update(pose_at(0, 0), 0.0);
  EXPECT_FALSE(host.last_had_costmap());
  costmap.resolution = 0.1;
  const BehaviorStep step = s.cycle_update(pose_at(-0.01, 0), 0.1);
  EXPECT_TRUE(step.error.empty()) << step.error;
  EXPECT_TRUE(host.last_had_costmap());
  s.cycle_update(pose_at(-0.02, 0), 0.2);
  EXPECT_FALSE(host.last_had_costmap());
}

TEST_F(BehaviorSessionTest, EveryFailureIsAFailedStepNeverAnException)
{
  auto & s = make();
  // the behaviour refuses the goal
  const BehaviorStep refused = s.run(kBackUp, backup(-0.3, 0.0), pose_at(0, 0));
  EXPECT_EQ(refused.status, BehaviorStatus::Failed);
  EXPECT_EQ(refused.failure, BehaviorFailure::InvalidInput);
  EXPECT_FALSE(s.running());
  ASSERT_EQ(s.run(kBackUp, backup(-0.3, 0.1), pose_at(0, 0)).status, BehaviorStatus::Succeeded);
  // a Python exception: FAILED, UNKNOWN, its traceback for the log
  host.error_once = proto::Error{
    "ControllerException", "Creep.on_cycle_update: KeyError: 'x'",
    "Traceback (most recent call last):\n  File \"creep.py\", line 3\nKeyError: 'x'\n",
    "builtins.KeyError"};
  const BehaviorStep raised = s.cycle_update(pose_at(0, 0), 0.1);
  EXPECT_EQ(raised.status, BehaviorStatus::Failed);
  EXPECT_EQ(raised.failure, BehaviorFailure::Unknown);
  EXPECT_NE(raised.error.find("KeyError: 'x'"), std::string::npos) << raised.error;
  EXPECT_NE(raised.error.find("creep.py"), std::string::npos) << raised.error;
  // a non-finite command never reaches cmd_vel
  host.nan_once = true;
  const BehaviorStep nan = s.cycle_update(pose_at(0, 0), 0.2);
  EXPECT_EQ(nan.status, BehaviorStatus::Failed);
  EXPECT_FALSE(nan.cmd_vel.has_value());
  EXPECT_NE(nan.error.find("nan"), std::string::npos) << nan.error;
  // the wire's names; anything else is a bad reply (a FAILED step)
  const auto status = [](const char * name) {
      return protocol::from_name<BehaviorStatus>(protocol::kBehaviorStatusNames, name);
    };
  const auto failure = [](const char * name) {
      return protocol::from_name<BehaviorFailure>(protocol::kBehaviorFailureNames, name);
    };
  EXPECT_EQ(status("running"), BehaviorStatus::Running);
  EXPECT_EQ(status("flying"), std::nullopt);
  EXPECT_EQ(failure("collision_ahead"), BehaviorFailure::CollisionAhead);
  EXPECT_EQ(failure("Collision_Ahead"), std::nullopt);
  // no host at all: FAILED at once, nothing sent
  host.kill();
  const auto sent = host.received.size();
  const BehaviorStep gone = s.cycle_update(pose_at(0, 0), 0.4);
  EXPECT_EQ(gone.status, BehaviorStatus::Failed);
  EXPECT_EQ(gone.failure, BehaviorFailure::Unknown);
  EXPECT_NE(gone.error.find("no planner host is alive"), std::string::npos) << gone.error;
  EXPECT_EQ(host.received.size(), sent);
  s.action_completion("failed", 0.4);  // logged, not thrown
  EXPECT_TRUE(log.contains("on_action_completion failed"));
}

TEST_F(BehaviorSessionTest, ARestartedHostIsGivenTheActionUnderWayAgain)
{
  auto & s = make();
  ASSERT_EQ(s.run(kBackUp, backup(-0.3, 0.1), pose_at(2.0, 0)).status, BehaviorStatus::Succeeded);
  EXPECT_EQ(s.cycle_update(pose_at(1.9, 0), 1.0).status, BehaviorStatus::Running);
  host.restart();  // the new host knows no session
  const auto sent = host.received.size();
  const BehaviorStep step = s.cycle_update(pose_at(1.8, 0), 2.0);
  EXPECT_EQ(
    host.ops_since(sent), (std::vector<std::string>{"on_cycle_update", "configure", "activate",
      "on_run", "on_cycle_update"}));
  EXPECT_EQ(step.status, BehaviorStatus::Running);
  EXPECT_NEAR(number(step.feedback, "distance_traveled"), 0.2, 1e-9);  // from where it started
  EXPECT_EQ(number(step.feedback, "runs"), 1.0);
  EXPECT_EQ(s.state().resyncs, 1u);
  // once the action ended, a restart re-sends no on_run
  s.action_completion("succeeded", 2.0);
  host.restart();
  const auto later = host.received.size();
  s.run(kBackUp, backup(-0.3, 0.1), pose_at(0, 0));
  EXPECT_EQ(
    host.ops_since(later), (std::vector<std::string>{"on_run", "configure", "activate",
      "on_run"}));
}

TEST_F(BehaviorSessionTest, ACycleWaitsTheCallTimeoutARunTheLifecycleOne)
{
  Timeouts timeouts;
  EXPECT_EQ(timeouts.for_op(proto::Op::OnCycleUpdate), timeouts.call);
  EXPECT_EQ(timeouts.for_op(proto::Op::OnRun), timeouts.lifecycle);
  EXPECT_EQ(timeouts.for_op(proto::Op::OnActionCompletion), timeouts.lifecycle);
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
