#include "nav2_pyif_bridge/py_checkers.hpp"

#include <limits>
#include <utility>

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{
namespace
{

protocol::IsGoalReachedRequest goal_check(
  const geometry_msgs::msg::Pose & query_pose, const geometry_msgs::msg::Pose & goal_pose,
  const geometry_msgs::msg::Twist & velocity)
{
  return client::goal_check(
    ros::pose_row(query_pose), ros::pose_row(goal_pose), ros::to_wire(velocity));
}

}  // namespace

void PyGoalChecker::initialize(
  const Nav2Node::WeakPtr & parent, const std::string & plugin_name,
  const std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
{
  tolerances_.reset();
  costmap_ros_ = costmap_ros;
  plugin_.start(parent, plugin_name, bind_costmap(costmap_ros));
}

void PyGoalChecker::reset()
{
  plugin_.bridge().forward(
    [this]() {
      tolerances_.reset();
      plugin_.session().call(protocol::ResetRequest{});
    });
}

bool PyGoalChecker::isGoalReached(
  const geometry_msgs::msg::Pose & query_pose, const geometry_msgs::msg::Pose & goal_pose,
  const geometry_msgs::msg::Twist & velocity
#if NAV2_PYIF_LYRICAL_API
  , const nav_msgs::msg::Path &
#endif
)
{
  // controller_server's pose lookup once more: the same message (its stamp included) when
  // TF has not moved on, which the cycle's other calls then get (goal check first).
  client::CarriedCycle * cycle = plugin_.session().cycle();
  geometry_msgs::msg::PoseStamped robot;
  const bool looked_up = cycle && !cycle->goal_last() && costmap_ros_ &&
    costmap_ros_->getRobotPose(robot) && robot.pose == query_pose;
  const std::optional<protocol::GoalChecker> tolerances =
    looked_up ? ros::tolerances(this) : std::nullopt;
  return plugin_.bridge().forward(
    [&]() {
      const protocol::IsGoalReachedRequest request = goal_check(query_pose, goal_pose, velocity);
      if (cycle) {
        return cycle->is_goal_reached(
          plugin_.session(),
          looked_up ? std::make_optional(ros::to_wire(robot)) : std::nullopt, request, tolerances);
      }
      return plugin_.session().call(request).reached;
    });
}

#if NAV2_PYIF_LYRICAL_API
bool PyGoalChecker::isGoalXYReached(
  const geometry_msgs::msg::Pose & query_pose, const geometry_msgs::msg::Pose & goal_pose,
  const geometry_msgs::msg::Twist & velocity, const nav_msgs::msg::Path &)
{
  return plugin_.bridge().forward(
    [&]() {
      protocol::IsGoalReachedRequest request = goal_check(query_pose, goal_pose, velocity);
      request.xy_only = true;
      return plugin_.session().call(request).reached;
    });
}
#endif

bool PyGoalChecker::getTolerances(
  geometry_msgs::msg::Pose & pose_tolerance,
  geometry_msgs::msg::Twist & vel_tolerance
#if NAV2_PYIF_LYRICAL_API
  , double & path_length_tolerance
#endif
)
{
  return plugin_.bridge().forward(
    [&]() {
      const protocol::GetTolerancesReply & tolerances = cached_tolerances();
      pose_tolerance = ros::pose_of(tolerances.pose_tolerance.data());
      vel_tolerance = ros::twist_of(tolerances.velocity_tolerance);
#if NAV2_PYIF_LYRICAL_API
      path_length_tolerance = tolerances.path_length_tolerance.value_or(
        std::numeric_limits<double>::lowest());
#endif
      return tolerances.available;
    });
}

const protocol::GetTolerancesReply & PyGoalChecker::cached_tolerances()
{
  if (!tolerances_) {
    tolerances_ = plugin_.session().call(protocol::GetTolerancesRequest{});
  }
  return *tolerances_;
}

void PyProgressChecker::initialize(
  const Nav2Node::WeakPtr & parent, const std::string & plugin_name)
{
  CostmapBinding none;  // Nav2 gives a progress checker no costmap
  none.source = std::make_unique<client::NoCostmap>();
  plugin_.start(parent, plugin_name, std::move(none));
  if (client::CarriedCycle * cycle = plugin_.session().cycle()) {
    cycle->use_progress_checker(plugin_.session());
  }
  auto node = parent.lock();
  if (node && node->has_parameter("failure_tolerance")) {
    failure_tolerance_ = node->get_parameter("failure_tolerance").as_double();
  }
}

bool PyProgressChecker::unanswered(const client::CallError & error)
{
  if (!error.host_failed()) {
    return false;  // the checker's own answer (an exception of the Python checker) stands
  }
  const rclcpp::Time now = plugin_.bridge().clock()->now();
  if (!unanswered_since_) {
    unanswered_since_ = now;
  }
  const double seconds = (now - *unanswered_since_).seconds();
  // (Nav2's meaning: 0 tolerates nothing, -1 everything)
  if (failure_tolerance_ == 0.0 || (failure_tolerance_ > 0.0 && seconds > failure_tolerance_)) {
    return false;
  }
  RCLCPP_WARN_THROTTLE(
    plugin_.bridge().ros_logger(), *plugin_.bridge().clock(), 1000,
    "%s; no verdict for %.2f s, taken as progressing for up to failure_tolerance (%.2f s)",
    error.what(), seconds, failure_tolerance_);
  return true;
}

bool PyProgressChecker::check(geometry_msgs::msg::PoseStamped & current_pose)
{
  return plugin_.bridge().forward(
    [&]() {
      const auto request = client::progress_check(ros::to_wire(current_pose));
      client::ProgressCheckerSession & session = plugin_.session();
      // The answer the goal check's query carried, when it was prepared for this pose;
      // else a check that carries the command
      client::CarriedCycle * cycle = session.cycle();
      try {
        const bool progressing =
          cycle ? cycle->check(session, request) : session.call(request).making_progress;
        unanswered_since_.reset();
        return progressing;
      } catch (const client::CallError & error) {
        if (unanswered(error)) {
          return true;
        }
        throw;
      }
    });
}

void PyProgressChecker::reset()
{
  unanswered_since_.reset();
  plugin_.bridge().forward(
    [this]() {
      if (client::CarriedCycle * cycle = plugin_.session().cycle()) {
        cycle->use_progress_checker(plugin_.session());  // the new goal's progress checker
      }
      plugin_.session().call(protocol::ResetRequest{});
    });
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyGoalChecker, nav2_core::GoalChecker)
PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyProgressChecker, nav2_core::ProgressChecker)
