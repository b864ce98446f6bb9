#include "nav2_pyif_bridge/py_controller.hpp"

#include <optional>

#include "pluginlib/class_list_macros.hpp"
#include "tf2/utils.h"

#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

namespace
{

// The goal checker's tolerances, as the protocol carries them (std::nullopt without one).
std::optional<protocol::GoalChecker> tolerances(nav2_core::GoalChecker * goal_checker)
{
  if (goal_checker == nullptr) {
    return std::nullopt;
  }
  geometry_msgs::msg::Pose pose_tolerance;
  geometry_msgs::msg::Twist velocity_tolerance;
  if (!goal_checker->getTolerances(pose_tolerance, velocity_tolerance)) {
    return std::nullopt;
  }
  return protocol::GoalChecker{
    pose_tolerance.position.x, tf2::getYaw(pose_tolerance.orientation),
    velocity_tolerance.linear.x, velocity_tolerance.angular.z};
}

}  // namespace

void PyController::cleanup()
{
  PyPlugin::cleanup();
  plan_.clear();
}

void PyController::setPlan(const nav_msgs::msg::Path & path)
{
  bridge_->forward(
    [&]() {
      if (reset_owed_) {
        reset_owed_ = false;
        send_reset();
      }
      session_->set_plan(ros::to_wire(plan_.set(
        path, costmap_ros_->getGlobalFrameID(), *tf_, bridge_->transform_tolerance())));
    });
}

geometry_msgs::msg::TwistStamped PyController::computeVelocityCommands(
  const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
  nav2_core::GoalChecker * goal_checker)
{
  return bridge_->forward(
    [&]() {
      const geometry_msgs::msg::PoseStamped global = ros::in_frame(
        pose, costmap_ros_->getGlobalFrameID(), *tf_, bridge_->transform_tolerance(),
        client::ErrorKind::ControllerTFError);
      if (auto fresh = plan_.refreshed(
          costmap_ros_->getGlobalFrameID(), *tf_, bridge_->transform_tolerance()))
      {
        session_->set_plan(ros::to_wire(*fresh));  // localisation moved the plan's frame
      }
      try {
        const protocol::TwistStamped cmd = session_->compute_velocity_commands(
          ros::to_wire(global), ros::to_wire(velocity), tolerances(goal_checker));
        host_silent_ = false;
        return ros::to_ros(cmd, costmap_ros_->getBaseFrameID(), pose.header.stamp);
      } catch (const client::CallError & error) {
        host_silent_ = error.cause() == client::Cause::TimedOut;
        throw;
      }
    });
}

void PyController::setSpeedLimit(const double & speed_limit, const bool & percentage)
{
  try {
    session_->set_speed_limit(speed_limit, percentage);
  } catch (const client::CallError & error) {
    RCLCPP_WARN(
      bridge_->ros_logger(), "%s: speed limit %.3f%s: %s", name_.c_str(), speed_limit,
      percentage ? " %" : " m/s", error.log_text().c_str());
  }
}

#if NAV2_PYIF_JAZZY_API
bool PyController::cancel()
{
  try {
    return session_->cancel();
  } catch (const client::CallError & error) {
    RCLCPP_WARN(bridge_->ros_logger(), "%s: cancel: %s", name_.c_str(), error.what());
    return true;
  }
}

void PyController::reset()
{
  if (host_silent_) {
    reset_owed_ = true;  // Nav2 reports the abort only after this returns: do not wait again
    return;
  }
  send_reset();
}
#endif

void PyController::send_reset()
{
  try {
    session_->reset(session_->timeouts().call);
  } catch (const client::CallError & error) {
    RCLCPP_DEBUG(bridge_->ros_logger(), "%s: reset: %s", name_.c_str(), error.what());
  }
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyController, nav2_core::Controller)
