// nav2_pyif_bridge::PyGoalChecker and PyProgressChecker: controller_server's goal and progress
// checkers answered by Python checkers in a planner host, over Zenoh. Nav2 only initializes
// checkers: the session is configured at initialize and ends when the checker is destroyed.
// With a Python controller and progress checker in the same controller_server, a call's query
// carries the calls of the cycle that follow it (PROTOCOL.md section 15, carried_cycle.hpp):
// one round trip per cycle when Nav2 checks the goal first, two when it checks it last.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "geometry_msgs/msg/pose.hpp"
#include "geometry_msgs/msg/pose_stamped.hpp"
#include "geometry_msgs/msg/twist.hpp"
#include "nav2_core/goal_checker.hpp"
#include "nav2_core/progress_checker.hpp"
#include "nav2_costmap_2d/costmap_2d_ros.hpp"
#include "nav_msgs/msg/path.hpp"

#include "nav2_pyif_bridge/bridged_session.hpp"
#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge
{

class PyGoalChecker : public nav2_core::GoalChecker
{
public:
  void initialize(
    const Nav2Node::WeakPtr & parent, const std::string & plugin_name,
    const std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros) override;
  // Every new goal: the checker's reset, then its tolerances again (they are cached between:
  // a controller asks for them every cycle, and a parameter change shows from the next goal).
  void reset() override;
  // Lyrical's checks also take the transformed plan (not forwarded: the Python checker has the
  // poses, PROTOCOL.md section 14), and its tolerances the path length's: lowest() (Nav2's
  // "not measured") when the host gives none.
  bool isGoalReached(
    const geometry_msgs::msg::Pose & query_pose, const geometry_msgs::msg::Pose & goal_pose,
    const geometry_msgs::msg::Twist & velocity
#if NAV2_PYIF_LYRICAL_API
    , const nav_msgs::msg::Path &
#endif
  ) override;
  bool getTolerances(
    geometry_msgs::msg::Pose & pose_tolerance, geometry_msgs::msg::Twist & vel_tolerance
#if NAV2_PYIF_LYRICAL_API
    , double & path_length_tolerance
#endif
  ) override;
#if NAV2_PYIF_LYRICAL_API
  bool isGoalXYReached(
    const geometry_msgs::msg::Pose & query_pose, const geometry_msgs::msg::Pose & goal_pose,
    const geometry_msgs::msg::Twist & velocity, const nav_msgs::msg::Path &) override;
#endif

private:
  // The tolerances, asked once per goal.
  const protocol::GetTolerancesReply & cached_tolerances();

  BridgedSession<client::GoalCheckerSession> plugin_;
  std::optional<protocol::GetTolerancesReply> tolerances_;
  // The robot's pose as controller_server looks it up (header included): what the carried
  // progress check and command are prepared with.
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
};

class PyProgressChecker : public nav2_core::ProgressChecker
{
public:
  void initialize(
    const Nav2Node::WeakPtr & parent,
    const std::string & plugin_name) override;
  bool check(geometry_msgs::msg::PoseStamped & current_pose) override;
  void reset() override;

private:
  // A check the host did not answer (dead, stopped, too slow) gives no verdict: the robot is
  // taken as progressing for up to controller_server's failure_tolerance, the time Nav2 grants
  // a failing controller, and the check fails after that. Without it one late reply aborted
  // the goal, where the same late reply to the controller is tolerated.
  bool unanswered(const client::CallError & error);

  BridgedSession<client::ProgressCheckerSession> plugin_;
  double failure_tolerance_{0.0};  // [s] controller_server's (0: none, -1: without end)
  std::optional<rclcpp::Time> unanswered_since_;
};

}  // namespace nav2_pyif_bridge
