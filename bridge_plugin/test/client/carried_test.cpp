// Requests carried in another call's query (PROTOCOL.md section 15), plugin side: prepared
// calls answered by a fake host, then used only when Nav2's call is the prepared one; the
// carried cycle in both of controller_server's orders; sessions leaving the cycle.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fakes.hpp"
#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/client/path_handler_session.hpp"

namespace nav2_pyif_bridge::client::test
{
namespace
{

namespace proto = protocol;
const char * const kKey = "nav2_pyif/test_robot/FollowPath";
const std::array<double, 6> kVelocity{0.3, 0.0, 0.0, 0.0, 0.0, 0.1};
const proto::GoalChecker kTolerances{0.25, 0.3, 0.05, 0.1, std::nullopt};

class CarriedTest : public ::testing::Test
{
protected:
  static SessionConfig session_config()
  {
    SessionConfig config;
    config.key_prefix = kKey;
    config.name = "FollowPath";
    config.node = "controller_server";
    config.global_frame = "odom";
    config.timeouts.call = 2s;
    return config;
  }

  void SetUp() override
  {
    session = std::make_unique<ControllerSession>(session_config(), host, costmap, log.logger());
    session->configure();
    session->activate();
    session->set_plan(straight_path(40, 3.0, 0.0));
  }

  // What the goal check's host does with a carried request: answers it as if it had come on
  // its own key.
  std::optional<proto::Bytes> run(const Carried & carried)
  {
    const proto::Op op = carried.request.op();
    return host.query(Target{session->keys().call(op), ""}, carried.payload, 2s, nullptr);
  }

  // A goal checker and a progress checker of controller_server, configured.
  struct Checkers
  {
    std::unique_ptr<GoalCheckerSession> goal;
    std::unique_ptr<ProgressCheckerSession> progress;
  };
  Checkers checkers(const Timeouts & timeouts)
  {
    SessionConfig config;
    config.node = "controller_server";
    config.global_frame = "odom";
    config.timeouts = timeouts;
    config.key_prefix = "nav2_pyif/test_robot/goal_checker";
    config.name = "goal_checker";
    Checkers made{std::make_unique<GoalCheckerSession>(config, host, costmap, log.logger()), {}};
    config.key_prefix = "nav2_pyif/test_robot/progress_checker";
    config.name = "progress_checker";
    made.progress = std::make_unique<ProgressCheckerSession>(config, host, costmap, log.logger());
    made.goal->configure();
    made.progress->configure();
    return made;
  }

  Carried prepare()
  {
    auto prepared = session->prepare_command(pose_at(1.0, 1.0), kVelocity, kTolerances);
    EXPECT_TRUE(prepared.has_value());
    return *prepared;
  }

  FakeClock clock;
  FakeHost host{clock};
  GridCostmap costmap;
  LogSink log;
  std::unique_ptr<ControllerSession> session;
};

TEST_F(CarriedTest, ThePreparedCommandIsUsedWhenNav2CallsWithTheSameInputs)
{
  const Carried prepared = prepare();
  const auto reply = run(prepared);
  const std::size_t queries = host.received.size();
  const auto cmd =
    session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances);
  ASSERT_TRUE(cmd.has_value());
  // the fake host echoes: plan size, default gain, no speed limit, costmap v1, tolerances, call 1
  EXPECT_EQ(cmd->twist, (std::array<double, 6>{40.0, 1.5, -1.0, 1.0, 1.0, 1.0}));
  EXPECT_EQ(host.received.size(), queries);  // nothing more sent
  // the costmap it carried counts as delivered: the next cycle sends none
  session->compute_velocity_commands(pose_at(1.0, 1.0), kVelocity, kTolerances);
  EXPECT_FALSE(host.last_had_costmap());
  EXPECT_GT(host.last().seq, prepared.request.seq);
}

// The inputs attached: those of the last request the host got, when it was a command.
std::vector<std::string> inputs_sent(const FakeHost & host)
{
  std::vector<std::string> names;
  const auto & body = std::get<proto::ComputeVelocityCommandsRequest>(host.last().body);
  for (const auto & input : body.inputs.value_or(std::vector<proto::Input>{})) {
    names.push_back(input.name + "@" + std::to_string(input.stamp_ns));
  }
  return names;
}

TEST_F(CarriedTest, TheInputsACarriedCommandTookAreAcknowledgedANewerOneIsNot)
{
  session->set_input(proto::Input{"scan", "sensor_msgs/msg/LaserScan", 1, {0, 1, 0, 0, 7}});
  Carried prepared = prepare();
  auto reply = run(prepared);
  EXPECT_EQ(inputs_sent(host), (std::vector<std::string>{"scan@1"}));
  ASSERT_TRUE(session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances));
  session->compute_velocity_commands(pose_at(1.0, 1.0), kVelocity, kTolerances);
  EXPECT_EQ(inputs_sent(host), std::vector<std::string>{});  // the host has it

  // a scan that arrives between the prepared command and Nav2's: the call goes on its own,
  // with it
  prepared = prepare();
  reply = run(prepared);
  session->set_input(proto::Input{"scan", "sensor_msgs/msg/LaserScan", 2, {0, 1, 0, 0, 8}});
  EXPECT_FALSE(session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances));
  session->compute_velocity_commands(pose_at(1.0, 1.0), kVelocity, kTolerances);
  EXPECT_EQ(inputs_sent(host), (std::vector<std::string>{"scan@2"}));
  session->compute_velocity_commands(pose_at(1.0, 1.0), kVelocity, kTolerances);
  EXPECT_EQ(inputs_sent(host), std::vector<std::string>{});
}

TEST_F(CarriedTest, AnyOtherInputMakesTheCallGoOnItsOwn)
{
  auto other_stamp = pose_at(1.0, 1.0);
  other_stamp.stamp_ns += 1;
  auto other_frame = pose_at(1.0, 1.0, "map");
  std::array<double, 6> faster = kVelocity;
  faster[0] += 0.01;
  proto::GoalChecker looser = kTolerances;
  looser.xy_goal_tolerance = 0.5;
  for (const auto & [pose, velocity, tolerances] :
    {std::tuple{other_stamp, kVelocity, std::optional{kTolerances}},
      std::tuple{other_frame, kVelocity, std::optional{kTolerances}},
      std::tuple{pose_at(1.0, 1.0), faster, std::optional{kTolerances}},
      std::tuple{pose_at(1.0, 1.0), kVelocity, std::optional{looser}},
      std::tuple{pose_at(1.0, 1.0), kVelocity, std::optional<proto::GoalChecker>{}}})
  {
    const Carried prepared = prepare();
    EXPECT_FALSE(session->take_command(prepared, run(prepared), pose, velocity,
      tolerances).has_value());
  }
}

TEST_F(CarriedTest, ACostmapOrPlanChangedSinceMakesTheCallGoOnItsOwn)
{
  Carried prepared = prepare();
  auto reply = run(prepared);
  costmap.data[5] = 99;
  EXPECT_FALSE(
    session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances));

  prepared = prepare();
  reply = run(prepared);
  session->set_plan(straight_path(10, 1.0, 0.0));  // localisation moved the plan's frame
  EXPECT_FALSE(
    session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances));
}

TEST_F(CarriedTest, NoReplyUnavailableOrSessionUnknownMakeTheCallGoOnItsOwn)
{
  Carried prepared = prepare();
  EXPECT_FALSE(session->take_command(
    prepared, std::nullopt, pose_at(1.0, 1.0), kVelocity, kTolerances));  // did not run

  prepared = prepare();
  host.restart();  // the new host knows no session
  EXPECT_FALSE(session->take_command(
    prepared, run(prepared), pose_at(1.0, 1.0), kVelocity, kTolerances));

  prepared = prepare();
  host.error_once = proto::Error{"Unavailable", "restarting", "", ""};
  EXPECT_FALSE(session->take_command(
    prepared, run(prepared), pose_at(1.0, 1.0), kVelocity, kTolerances));
}

TEST_F(CarriedTest, AnErrorReplyIsTheCallsError)
{
  Carried prepared = prepare();
  host.error_once = proto::Error{"NoValidControl", "blocked", "Traceback ...", "x.Y"};
  const auto reply = run(prepared);
  const CallError e = error_of([&] {
        session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances);
      });
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
  EXPECT_EQ(std::string(e.what()), "blocked");

  prepared = prepare();
  const CallError bad = error_of([&] {
        session->take_command(
          prepared, proto::Bytes{1, 2, 3}, pose_at(1.0, 1.0), kVelocity, kTolerances);
      });
  EXPECT_EQ(bad.cause(), Cause::BadReply);
}

TEST_F(CarriedTest, ANonFiniteCarriedCommandIsRefusedAsOnItsOwn)
{
  const Carried prepared = prepare();
  host.nan_once = true;
  const auto reply = run(prepared);
  const CallError e = error_of([&] {
        session->take_command(prepared, reply, pose_at(1.0, 1.0), kVelocity, kTolerances);
      });
  EXPECT_EQ(e.kind(), ErrorKind::NoValidControl);
}

TEST_F(CarriedTest, NothingIsPreparedBeforeTheSessionIsEstablished)
{
  session->cleanup();
  EXPECT_FALSE(session->prepare_command(pose_at(1.0, 1.0), kVelocity, kTolerances));
}

TEST_F(CarriedTest, TheCycleUsesACarriedAnswerOnceAndForgetsALeavingSession)
{
  auto cycle = CarriedCycle::of("/carried_test_controller_server");
  EXPECT_EQ(cycle, CarriedCycle::of("/carried_test_controller_server"));
  EXPECT_NE(cycle, CarriedCycle::of("/another_controller_server"));
  session->join(cycle);
  cycle->use_controller(*session);
  // Nothing pending: the controller calls on its own.
  const std::size_t before = host.received.size();
  cycle->compute_velocity_commands(*session, pose_at(1.0, 1.0), kVelocity, kTolerances);
  EXPECT_EQ(host.ops_since(before), (std::vector<std::string>{"compute_velocity_commands"}));
  session.reset();  // destroyed: leaves the cycle, which then prepares nothing for it
  EXPECT_EQ(cycle->carried_used(), 0u);
}

TEST_F(CarriedTest, TheCheckersResetIsAControlLoopCallNotALifecycleOne)
{
  // Nav2 resets the checkers after every goal, inside controller_server's loop: a silent
  // host may hold it up for the call timeout, never the 5 s lifecycle one (schema.py
  // OP_TIMEOUT, the same table the reference client and the host read).
  Timeouts timeouts;
  timeouts.call = 40ms;
  timeouts.lifecycle = 5s;
  const Checkers made = checkers(timeouts);
  host.call_time = 100s;
  for (const auto & reset : std::vector<std::function<void()>>{
      [&made] {made.goal->call(proto::ResetRequest{});},
      [&made] {made.progress->call(proto::ResetRequest{});}})
  {
    const Duration before = clock.elapsed();
    EXPECT_THROW(reset(), CallError);
    EXPECT_EQ(clock.elapsed() - before, Duration{40ms});
  }
}

TEST_F(CarriedTest, AProgressCheckForAMovedPoseCarriesTheCommandPreparedForIt)
{
  Timeouts timeouts;
  timeouts.call = 2s;
  auto made = checkers(timeouts);
  GoalCheckerSession & goal_checker = *made.goal;
  ProgressCheckerSession & progress_checker = *made.progress;
  auto cycle = CarriedCycle::of("/carried_test_moved_pose");
  session->join(cycle);
  progress_checker.join(cycle);
  cycle->use_controller(*session);
  cycle->use_progress_checker(progress_checker);
  const std::array<double, 7> goal{3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  const proto::PoseStamped robot = pose_at(1.0, 1.0);
  auto goal_check = [&] {
      return cycle->is_goal_reached(
        goal_checker, robot, client::goal_check(robot.pose, goal, kVelocity), kTolerances);
    };
  auto moved = pose_at(1.05, 1.0);  // TF moved on between Nav2's two pose lookups
  moved.stamp_ns += 20000000;

  std::size_t before = host.received.size();
  EXPECT_FALSE(goal_check());
  EXPECT_TRUE(cycle->check(progress_checker, progress_check(moved)));
  const auto cmd = cycle->compute_velocity_commands(*session, moved, kVelocity, kTolerances);
  EXPECT_EQ(cmd.twist[5], 2.0);  // its second run: the first was for the goal check's pose
  // two queries, not three: the command came in the check's reply
  EXPECT_EQ(host.ops_since(before), (std::vector<std::string>{"is_goal_reached", "check"}));
  EXPECT_EQ(host.carried_ops, (std::vector<std::string>{"check", "compute_velocity_commands",
    "compute_velocity_commands"}));
  const auto & carry = std::get<proto::CheckRequest>(host.last().body).carry;
  ASSERT_TRUE(carry.has_value());
  EXPECT_EQ(carry->at(0).key, kKey);

  // Another velocity than the goal check's (odometry moved on too): the command goes alone.
  before = host.received.size();
  EXPECT_FALSE(goal_check());
  EXPECT_TRUE(cycle->check(progress_checker, progress_check(moved)));
  std::array<double, 6> faster = kVelocity;
  faster[0] += 0.01;
  cycle->compute_velocity_commands(*session, moved, faster, kTolerances);
  EXPECT_EQ(
    host.ops_since(before),
    (std::vector<std::string>{"is_goal_reached", "check", "compute_velocity_commands"}));

  // No progress: Nav2 stops there, and so did the host: the carried command did not run.
  host.making_progress = false;
  host.carried_ops.clear();
  EXPECT_FALSE(goal_check());
  EXPECT_FALSE(cycle->check(progress_checker, progress_check(moved)));
  EXPECT_EQ(host.carried_ops, (std::vector<std::string>{"check"}));

  // The same pose as the goal check's: its carried answers are used, nothing more is sent.
  host.making_progress = true;
  EXPECT_FALSE(goal_check());
  before = host.received.size();
  EXPECT_TRUE(cycle->check(progress_checker, progress_check(robot)));
  cycle->compute_velocity_commands(*session, robot, kVelocity, kTolerances);
  EXPECT_EQ(host.ops_since(before), (std::vector<std::string>{}));
  EXPECT_FALSE(cycle->goal_last());
}

TEST_F(CarriedTest, GoalLastAResetOrAMovedPoseSendsTheGoalCheckOnItsOwn)
{
  Timeouts timeouts;
  timeouts.call = 2s;
  auto made = checkers(timeouts);
  GoalCheckerSession & goal_checker = *made.goal;
  auto cycle = CarriedCycle::of("/carried_test_goal_last");
  session->join(cycle);
  cycle->use_controller(*session);
  const std::array<double, 7> goal{3.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  auto command_then_goal_check = [&](const proto::PoseStamped & robot, const auto & looked_up) {
      cycle->compute_velocity_commands(*session, robot, kVelocity, kTolerances);
      return cycle->is_goal_reached(
        goal_checker, std::nullopt, goal_check(looked_up.pose, goal, kVelocity), std::nullopt);
    };
  command_then_goal_check(pose_at(0.5, 1.0), pose_at(0.5, 1.0));  // shows the order
  ASSERT_TRUE(cycle->goal_last());
  std::size_t before = host.received.size();
  command_then_goal_check(pose_at(0.6, 1.0), pose_at(0.6, 1.0));
  EXPECT_EQ(host.ops_since(before), (std::vector<std::string>{"compute_velocity_commands"}));
  EXPECT_EQ(host.carried_ops.back(), "is_goal_reached");
  // A reset (a new plan): the goal checker may have another goal; the command carries none.
  goal_checker.call(proto::ResetRequest{});
  before = host.received.size();
  command_then_goal_check(pose_at(0.7, 1.0), pose_at(0.7, 1.0));
  EXPECT_EQ(
    host.ops_since(before),
    (std::vector<std::string>{"compute_velocity_commands", "is_goal_reached"}));
  // TF moved on between the command's pose lookup and the goal check's: on its own.
  before = host.received.size();
  command_then_goal_check(pose_at(0.8, 1.0), pose_at(0.81, 1.0));
  EXPECT_EQ(
    host.ops_since(before),
    (std::vector<std::string>{"compute_velocity_commands", "is_goal_reached"}));
  EXPECT_TRUE(cycle->goal_last());  // a cycle that fits neither order changes nothing
  EXPECT_EQ(cycle->carried_used(), 1u);
}

// What one control cycle's calls answered, in controller_server's order (`goal_last`: the goal
// check ends the cycle, as in Humble), up to where Nav2 stops (the goal reached).
std::vector<double> drive(
  bool goal_last, const std::function<bool()> & goal_check, const std::function<bool()> & check,
  const std::function<proto::TwistStamped()> & compute)
{
  std::vector<double> seen;
  auto goal = [&] {
      seen.push_back(goal_check() ? 1.0 : 0.0);
      return seen.back() == 1.0;
    };
  if (!goal_last && goal()) {
    return seen;
  }
  if (check) {
    seen.push_back(check() ? 1.0 : 0.0);
  }
  const auto cmd = compute();
  seen.insert(seen.end(), cmd.twist.begin(), cmd.twist.end());
  if (goal_last) {
    goal();
  }
  return seen;
}

// Queries per cycle, each order, and the answers of the same calls each sent on its own.
class CarriedOrderTest : public CarriedTest, public ::testing::WithParamInterface<bool>
{
protected:
  // The queries `steps` cycles took, the robot moving on between cycles and arriving in the
  // last; with a Python progress checker when `progress`.
  std::size_t run_cycles(bool goal_last, bool progress, int steps = 5)
  {
    Timeouts timeouts;
    timeouts.call = 2s;
    auto made = checkers(timeouts);
    auto cycle = CarriedCycle::of(goal_last ? "/order_last" : "/order_first");
    session->join(cycle);
    cycle->use_controller(*session);
    if (progress) {
      made.progress->join(cycle);
      cycle->use_progress_checker(*made.progress);
    }
    // the same plugins on their own: a controller with the same plan, checkers
    ControllerSession alone(session_config(), host, costmap, log.logger());
    alone.configure();
    alone.activate();
    alone.set_plan(straight_path(40, 3.0, 0.0));
    auto plain = checkers(timeouts);
    const std::array<double, 7> goal{2.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    host.reached_x = 2.0;
    std::size_t queries = 0;
    for (int step = 0; step < steps; ++step) {
      proto::PoseStamped robot = pose_at(0.5 + 0.375 * step, 1.0);
      robot.stamp_ns += step * 50000000;
      std::size_t before = host.received.size();
      const std::vector<double> carried = drive(
        goal_last,
        [&] {
          return cycle->is_goal_reached(
            *made.goal, robot, goal_check(robot.pose, goal, kVelocity), kTolerances);
        },
        progress ? std::function<bool()>{
          [&] {return cycle->check(*made.progress, progress_check(robot));}} : nullptr,
        [&] {return cycle->compute_velocity_commands(*session, robot, kVelocity, kTolerances);});
      queries += host.received.size() - before;
      const std::vector<double> uncarried = drive(
        goal_last,
        [&] {return plain.goal->call(goal_check(robot.pose, goal, kVelocity)).reached;},
        progress ? std::function<bool()>{
          [&] {return plain.progress->call(progress_check(robot)).making_progress;}} : nullptr,
        [&] {return alone.compute_velocity_commands(robot, kVelocity, kTolerances).cmd_vel;});
      EXPECT_EQ(carried, uncarried) << "cycle " << step;
    }
    EXPECT_EQ(cycle->goal_last(), goal_last);
    return queries;
  }
};

TEST_P(CarriedOrderTest, GoalCheckFirstTakesOneQueryPerCycle)
{
  EXPECT_EQ(run_cycles(false, GetParam()), 5u);  // the goal check carries the rest
}

TEST_P(CarriedOrderTest, GoalCheckLastTakesTwoWithAProgressCheckerElseOne)
{
  // The first goal check shows the order; from then on the command carries the goal check
  // and the progress check goes on its own.
  EXPECT_EQ(run_cycles(true, GetParam()), GetParam() ? 11u : 6u);
}

INSTANTIATE_TEST_SUITE_P(
  ProgressChecker, CarriedOrderTest, ::testing::Bool(),
  [](const ::testing::TestParamInfo<bool> & info) {
    return info.param ? "WithProgressChecker" : "GoalCheckerOnly";
  });

// Lyrical's cycle: the goal check, the progress check, the path handler's segment, then the
// command with the segment's plan (which it needs, so it cannot be prepared before).
TEST_F(CarriedTest, ThePathHandlersSegmentRidesWithTheChecksNoQueryOfItsOwn)
{
  Timeouts timeouts;
  timeouts.call = 2s;
  auto made = checkers(timeouts);
  SessionConfig config;
  config.node = "controller_server";
  config.global_frame = "odom";
  config.timeouts = timeouts;
  config.key_prefix = "nav2_pyif/test_robot/path_handler";
  config.name = "path_handler";
  PathHandlerSession handler(config, host, costmap, log.logger());
  handler.configure();
  EXPECT_FALSE(handler.set_plan(straight_path(40, 3.0, 0.0)).has_value());
  auto cycle = CarriedCycle::of("/carried_test_path_handler");
  for (PluginSession * member : {static_cast<PluginSession *>(session.get()),
      static_cast<PluginSession *>(made.goal.get()), static_cast<PluginSession *>(made.progress.get()),
      static_cast<PluginSession *>(&handler)})
  {
    member->join(cycle);
  }
  cycle->use_controller(*session);
  cycle->use_progress_checker(*made.progress);
  const std::array<double, 7> goal{3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  // one Lyrical cycle: the segment's and the command's answers, and the queries it took
  // (`python`: the segment is the Python path handler's; else Nav2's own, a fixed one)
  auto lyrical_cycle = [&](
    const proto::PoseStamped & robot, const proto::PoseStamped & moved, bool python) {
      const std::size_t before = host.received.size();
      EXPECT_FALSE(cycle->is_goal_reached(
        *made.goal, robot, goal_check(robot.pose, goal, kVelocity), kTolerances));
      EXPECT_TRUE(cycle->check(*made.progress, progress_check(moved)));
      const auto segment = python ? cycle->find_plan_segment(handler, moved) :
        std::pair<std::size_t, std::size_t>{0, 5};
      proto::Path part = straight_path(segment.second - segment.first, 3.0, 0.0);
      session->follow(part, pose_at(3.0, 0.0));
      cycle->compute_velocity_commands(*session, moved, kVelocity, kTolerances);
      return std::make_pair(segment, host.received.size() - before);
    };

  // Without the path handler in the cycle (Nav2's own): the checks' query, then the command's.
  for (double x : {0.3, 0.5}) {
    EXPECT_EQ(lyrical_cycle(pose_at(x, 0.0), pose_at(x, 0.0), false).second, 2u);
  }
  // With it: the goal check's query carries the check and the segment: still two queries.
  cycle->use_path_handler(handler);
  host.carried_ops.clear();
  auto [segment, queries] = lyrical_cycle(pose_at(1.0, 0.0), pose_at(1.0, 0.0), true);
  EXPECT_EQ(segment, (std::pair<std::size_t, std::size_t>{10, 15}));
  EXPECT_EQ(queries, 2u);
  EXPECT_EQ(host.carried_ops, (std::vector<std::string>{"check", "find_plan_segment"}));
  // TF moved on between the goal check's pose lookup and the check's: the check goes on its
  // own, carrying the segment prepared for its pose; the command still has a query of its own.
  auto moved = pose_at(1.2, 0.0);
  moved.stamp_ns += 20000000;
  auto [later, three] = lyrical_cycle(pose_at(1.1, 0.0), moved, true);
  EXPECT_EQ(later, (std::pair<std::size_t, std::size_t>{12, 17}));
  EXPECT_EQ(three, 3u);
  // from carried replies: the three checks of the goal check's pose, two segments
  EXPECT_EQ(cycle->carried_used(), 5u);
  cycle->forget(handler);
}

TEST(CarriedCycleMembers, AreTheControllerServersPluginTypesOnly)
{
  // (schema.py CARRIES: the goal check, the progress check and the command carry each other;
  // Lyrical's path handler's segment is carried)
  for (const PluginKind kind :
    {PluginKind::Controller, PluginKind::GoalChecker, PluginKind::ProgressChecker,
      PluginKind::PathHandler})
  {
    EXPECT_TRUE(proto::in_carried_cycle(kind)) << plugin_type_name(kind);
  }
  for (const PluginKind kind :
    {PluginKind::GlobalPlanner, PluginKind::Smoother, PluginKind::CostmapLayer,
      PluginKind::Behavior})
  {
    EXPECT_FALSE(proto::in_carried_cycle(kind)) << plugin_type_name(kind);
  }
}

}  // namespace
}  // namespace nav2_pyif_bridge::client::test
