#include "nav2_pyif_bridge/py_global_planner.hpp"

#include <stdexcept>
#include <utility>

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

PyGlobalPlanner::~PyGlobalPlanner()
{
  session_.reset();
  bridge_.reset();
}

void PyGlobalPlanner::configure(
  const rclcpp_lifecycle::LifecycleNode::WeakPtr & parent, std::string name,
  std::shared_ptr<tf2_ros::Buffer> tf,
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
{
  auto node = parent.lock();
  if (!node) {
    throw std::runtime_error("nav2_pyif_bridge::PyGlobalPlanner: unable to lock the node");
  }
  name_ = std::move(name);
  tf_ = std::move(tf);
  costmap_ros_ = std::move(costmap_ros);
  session_.reset();
  bridge_ = std::make_unique<PluginBridge>(
    node, name_, client::PluginKind::GlobalPlanner, costmap_ros_);
  session_ = std::make_unique<client::PlannerSession>(
    bridge_->session_config(), bridge_->transport(), bridge_->costmap(), bridge_->logger());
  bridge_->configure(*session_);
}

void PyGlobalPlanner::cleanup()
{
  if (bridge_ && session_) {
    bridge_->cleanup(*session_);
  }
  session_.reset();
  bridge_.reset();
}

void PyGlobalPlanner::activate()
{
  bridge_->lifecycle("activate", [this]() {session_->activate();});
}

void PyGlobalPlanner::deactivate()
{
  bridge_->lifecycle("deactivate", [this]() {session_->deactivate();});
}

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
