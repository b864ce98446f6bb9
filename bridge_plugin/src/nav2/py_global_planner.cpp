#include "nav2_pyif_bridge/py_global_planner.hpp"

#include <utility>

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

void PyGlobalPlanner::configure(
  const Nav2Node::WeakPtr & parent, std::string name, std::shared_ptr<TfBuffer> tf,
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
{
  tf_ = std::move(tf);
  costmap_ros_ = std::move(costmap_ros);
  plugin_.start(parent, name, bind_costmap(costmap_ros_));
}

nav_msgs::msg::Path PyGlobalPlanner::createPlan(
  const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal
#if NAV2_PYIF_LYRICAL_API
  , const std::vector<geometry_msgs::msg::PoseStamped> & viapoints
#endif
#if NAV2_PYIF_JAZZY_API
  , std::function<bool()> cancel_checker
#endif
)
{
#if !NAV2_PYIF_LYRICAL_API
  const std::vector<geometry_msgs::msg::PoseStamped> viapoints;  // before Lyrical: none
#endif
#if !NAV2_PYIF_JAZZY_API
  const std::function<bool()> cancel_checker;  // Humble's planner server has none
#endif
  return plugin_.bridge().forward(
    [&]() {
      const std::string frame = costmap_ros_->getGlobalFrameID();
      const double tolerance = plugin_.bridge().transform_tolerance();
      const auto tf_error = client::ErrorKind::PlannerTFError;
      protocol::CreatePlanRequest request;
      request.start = ros::to_wire(ros::in_frame(start, frame, *tf_, tolerance, tf_error));
      request.goal = ros::to_wire(ros::in_frame(goal, frame, *tf_, tolerance, tf_error));
      if (!viapoints.empty()) {
        request.viapoints.emplace();
        request.viapoints->frame_id = frame;
        request.viapoints->stamp_ns = request.goal.stamp_ns;
        for (const geometry_msgs::msg::PoseStamped & viapoint : viapoints) {
          const auto pose = ros::to_wire(ros::in_frame(viapoint, frame, *tf_, tolerance, tf_error));
          auto & poses = request.viapoints->poses;
          poses.insert(poses.end(), pose.pose.begin(), pose.pose.end());
        }
      }
      const protocol::Path path = plugin_.session().create_plan(request, cancel_checker);
      return ros::to_ros(path, frame, plugin_.bridge().clock()->now());
    });
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyGlobalPlanner, nav2_core::GlobalPlanner)
