#include "nav2_pyif_bridge/py_global_planner.hpp"

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

#if NAV2_PYIF_JAZZY_API
nav_msgs::msg::Path PyGlobalPlanner::createPlan(
  const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
  std::function<bool()> cancel_checker)
{
  return plan(start, goal, cancel_checker);
}
#else
nav_msgs::msg::Path PyGlobalPlanner::createPlan(
  const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal)
{
  return plan(start, goal, {});
}
#endif

nav_msgs::msg::Path PyGlobalPlanner::plan(
  const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
  const std::function<bool()> & cancel_checker)
{
  return bridge_->forward(
    [&]() {
      const std::string frame = costmap_ros_->getGlobalFrameID();
      const double tolerance = bridge_->transform_tolerance();
      const auto tf_error = client::ErrorKind::PlannerTFError;
      const auto wire_start = ros::to_wire(ros::in_frame(start, frame, *tf_, tolerance, tf_error));
      const auto wire_goal = ros::to_wire(ros::in_frame(goal, frame, *tf_, tolerance, tf_error));
      const protocol::Path path = session_->create_plan(wire_start, wire_goal, cancel_checker);
      return ros::to_ros(path, frame, bridge_->clock()->now());
    });
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyGlobalPlanner, nav2_core::GlobalPlanner)
