#include "nav2_pyif_bridge/py_smoother.hpp"

#include <utility>

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/costmap_subscriber_source.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

void PySmoother::configure(
  const Nav2Node::WeakPtr & parent, std::string name,
  std::shared_ptr<TfBuffer>,
  std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> costmap_sub,
  std::shared_ptr<nav2_costmap_2d::FootprintSubscriber>)
{
  CostmapBinding costmap;
  // smoother_server's robot_base_frame; its costmap's frame is not known here (the
  // subscriber does not say it): paths are smoothed in their own frame.
  if (auto node = parent.lock(); node && node->has_parameter("robot_base_frame")) {
    costmap.robot_base_frame = node->get_parameter("robot_base_frame").as_string();
  }
  costmap.source = std::make_unique<CostmapSubscriberSource>(std::move(costmap_sub), "");
  plugin_.start(parent, name, std::move(costmap));
}

bool PySmoother::smooth(nav_msgs::msg::Path & path, const rclcpp::Duration & max_time)
{
  return plugin_.bridge().forward(
    [&]() {
      protocol::SmoothRequest request;
      request.path = ros::to_wire(path);
      request.max_time = max_time.seconds();
      const protocol::SmoothReply reply = plugin_.session().call(request);
      path = ros::to_ros(reply.path, path.header.frame_id, path.header.stamp);
      return reply.was_completed;
    });
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PySmoother, nav2_core::Smoother)
