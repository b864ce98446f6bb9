// nav2_pyif_bridge::PyGlobalPlanner: a nav2_core::GlobalPlanner whose plans come from a Python
// planner in a planner host, over Zenoh, with Nav2's cancel checker forwarded (Jazzy+).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "geometry_msgs/msg/pose_stamped.hpp"
#include "nav2_core/global_planner.hpp"
#include "nav2_costmap_2d/costmap_2d_ros.hpp"
#include "nav_msgs/msg/path.hpp"
#include "rclcpp_lifecycle/lifecycle_node.hpp"
#include "tf2_ros/buffer.h"

#include "nav2_pyif_bridge/client/planner_session.hpp"
#include "nav2_pyif_bridge/plugin_bridge.hpp"

namespace nav2_pyif_bridge
{

class PyGlobalPlanner : public nav2_core::GlobalPlanner
{
public:
  PyGlobalPlanner() = default;
  ~PyGlobalPlanner() override;

  void configure(
    const rclcpp_lifecycle::LifecycleNode::WeakPtr & parent, std::string name,
    std::shared_ptr<tf2_ros::Buffer> tf,
    std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros) override;
  void cleanup() override;
  void activate() override;
  void deactivate() override;

#if NAV2_PYIF_JAZZY_API
  nav_msgs::msg::Path createPlan(
    const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
    std::function<bool()> cancel_checker) override;
#else
  nav_msgs::msg::Path createPlan(
    const geometry_msgs::msg::PoseStamped & start,
    const geometry_msgs::msg::PoseStamped & goal) override;
#endif

private:
  nav_msgs::msg::Path plan(
    const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
    const std::function<bool()> & cancel_checker);

  std::string name_;
  std::shared_ptr<tf2_ros::Buffer> tf_;
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
  std::unique_ptr<PluginBridge> bridge_;
  std::unique_ptr<client::PlannerSession> session_;
};

}  // namespace nav2_pyif_bridge
