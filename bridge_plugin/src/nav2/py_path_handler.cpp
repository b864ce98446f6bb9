#include "nav2_pyif_bridge/py_path_handler.hpp"

#if NAV2_PYIF_LYRICAL_API

#include <optional>
#include <utility>

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"
#include "nav2_pyif_bridge/tf2_headers.hpp"

namespace nav2_pyif_bridge
{
namespace
{

geometry_msgs::msg::PoseStamped from_wire(const protocol::PoseStamped & pose)
{
  geometry_msgs::msg::PoseStamped out;
  out.header.frame_id = pose.frame_id;
  out.header.stamp = ros::from_ns(pose.stamp_ns);
  out.pose = ros::pose_of(pose.pose.data());
  return out;
}

}  // namespace

void PyPathHandler::initialize(
  const Nav2Node::WeakPtr & parent, const rclcpp::Logger &, const std::string & plugin_name,
  const std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros, TfBuffer::SharedPtr tf)
{
  name_ = plugin_name;
  costmap_ros_ = costmap_ros;
  tf_ = std::move(tf);
  plan_ = nav_msgs::msg::Path{};
  plugin_.start(parent, name_, bind_costmap(costmap_ros_));
  client::PathHandlerSession & session = plugin_.session();
  // The carried cycle looks the robot up in the costmap's frame; the segment wants the plan's.
  session.set_pose_in_plan_frame(
    [this](const protocol::PoseStamped & robot) -> std::optional<protocol::PoseStamped> {
      try {
        return ros::to_wire(in_plan_frame(from_wire(robot)));
      } catch (const client::CallError &) {
        return std::nullopt;  // the segment's own call says so, if it still cannot
      }
    });
  if (client::CarriedCycle * cycle = session.cycle()) {
    cycle->use_path_handler(session);
  }
}

std::string PyPathHandler::plan_frame() const
{
  return plan_.header.frame_id.empty() ? costmap_ros_->getGlobalFrameID() : plan_.header.frame_id;
}

geometry_msgs::msg::PoseStamped PyPathHandler::in_plan_frame(
  const geometry_msgs::msg::PoseStamped & pose)
{
  return ros::in_frame(
    pose, plan_frame(), *tf_, plugin_.bridge().transform_tolerance(),
    client::ErrorKind::ControllerTFError);
}

void PyPathHandler::setPlan(const nav_msgs::msg::Path & path)
{
  plugin_.bridge().forward(
    [&]() {
      plan_ = path;
      client::PathHandlerSession & session = plugin_.session();
      if (client::CarriedCycle * cycle = session.cycle()) {
        cycle->use_path_handler(session);  // controller_server's current one has the plan
      }
      if (const std::optional<client::CallError> deferred = session.set_plan(ros::to_wire(path))) {
        RCLCPP_WARN(
          plugin_.bridge().ros_logger(), "%s: plan kept, sent when the host answers: %s",
          name_.c_str(), deferred->log_text().c_str());
      }
    });
}

nav2_core::PathSegment PyPathHandler::findPlanSegment(
  const geometry_msgs::msg::PoseStamped & pose)
{
  return plugin_.bridge().forward(
    [&]() {
      if (plan_.poses.empty()) {
        throw client::CallError(
                client::ErrorKind::InvalidPath, client::Cause::Local,
                "Received plan with zero length");
      }
      const geometry_msgs::msg::PoseStamped robot = in_plan_frame(pose);
      stamp_ = pose.header.stamp;
      client::PathHandlerSession & session = plugin_.session();
      client::CarriedCycle * cycle = session.cycle();
      const protocol::PoseStamped wire = ros::to_wire(robot);
      // The segment another call's query carried, when prepared for this pose; else its own
      const auto [start, end] =
        cycle ? cycle->find_plan_segment(session, wire) : session.find_plan_segment(wire);
      const auto begin = plan_.poses.begin();
      return nav2_core::PathSegment{
        begin + static_cast<std::ptrdiff_t>(start), begin + static_cast<std::ptrdiff_t>(end)};
    });
}

nav_msgs::msg::Path PyPathHandler::transformLocalPlan(
  const nav2_core::PathIterator & closest_point, const nav2_core::PathIterator & pruned_plan_end)
{
  return plugin_.bridge().forward(
    [&]() {
      const std::string & frame = costmap_ros_->getGlobalFrameID();
      nav_msgs::msg::Path out;
      out.header.frame_id = frame;
      out.header.stamp = stamp_;
      const geometry_msgs::msg::TransformStamped transform = ros::latest_transform(
        frame, plan_frame(), *tf_, plugin_.bridge().transform_tolerance(),
        client::ErrorKind::ControllerTFError, "the plan");
      const nav2_costmap_2d::Costmap2D & costmap = *costmap_ros_->getCostmap();
      for (auto pose = closest_point; pose != pruned_plan_end; ++pose) {
        geometry_msgs::msg::PoseStamped in_costmap;
        tf2::doTransform(*pose, in_costmap, transform);
        in_costmap.header.frame_id = frame;
        in_costmap.header.stamp = stamp_;
        unsigned int mx = 0;
        unsigned int my = 0;
        // cut at the costmap's edge, as Nav2's FeasiblePathHandler does
        if (!costmap.worldToMap(in_costmap.pose.position.x, in_costmap.pose.position.y, mx, my)) {
          break;
        }
        out.poses.push_back(std::move(in_costmap));
      }
      if (out.poses.empty()) {
        throw client::CallError(
                client::ErrorKind::InvalidPath, client::Cause::Local,
                "Resulting plan has 0 poses in it.");
      }
      return out;
    });
}

geometry_msgs::msg::PoseStamped PyPathHandler::getTransformedGoal(
  const builtin_interfaces::msg::Time & stamp)
{
  return plugin_.bridge().forward(
    [&]() {
      if (plan_.poses.empty()) {
        throw client::CallError(
                client::ErrorKind::InvalidPath, client::Cause::Local,
                "Received plan with zero length");
      }
      geometry_msgs::msg::PoseStamped goal = plan_.poses.back();
      goal.header.frame_id = plan_frame();
      goal.header.stamp = stamp;
      geometry_msgs::msg::PoseStamped out = ros::in_frame(
        goal, costmap_ros_->getGlobalFrameID(), *tf_, plugin_.bridge().transform_tolerance(),
        client::ErrorKind::ControllerTFError);
      out.header.frame_id = costmap_ros_->getGlobalFrameID();
      return out;
    });
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyPathHandler, nav2_core::PathHandler)

#endif  // NAV2_PYIF_LYRICAL_API
