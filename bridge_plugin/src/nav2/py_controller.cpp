#include "nav2_pyif_bridge/py_controller.hpp"

#include <array>
#include <cstring>
#include <optional>
#include <utility>

#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

void PyController::configure(
  const Nav2Node::WeakPtr & parent, std::string name,
  std::shared_ptr<TfBuffer> tf,
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
{
  name_ = std::move(name);
  tf_ = std::move(tf);
  costmap_ros_ = std::move(costmap_ros);
  plugin_.start(parent, name_, bind_costmap(costmap_ros_));
  node_ = parent;
  auto node = parent.lock();
  for (const client::InputSpec & spec : bridge().inputs()) {
    // Best effort with a short queue (SensorDataQoS) matches reliable publishers too; only
    // the latest message matters.
    input_subscriptions_.push_back(
      node->create_generic_subscription(
        spec.topic, spec.type, rclcpp::SensorDataQoS(),
        [this, spec, clock = bridge().clock()](std::shared_ptr<rclcpp::SerializedMessage> msg) {
          const rcl_serialized_message_t & raw = msg->get_rcl_serialized_message();
          protocol::Input input;
          input.name = spec.name;
          input.type = spec.type;
          input.stamp_ns = clock->now().nanoseconds();
          input.cdr.assign(raw.buffer, raw.buffer + raw.buffer_length);
          session().set_input(std::move(input));
        }));
    RCLCPP_INFO(
      bridge().ros_logger(), "%s: input '%s' from %s (%s)", name_.c_str(), spec.name.c_str(),
      spec.topic.c_str(), spec.type.c_str());
  }
  sync_debug_publishers();
}

void PyController::cleanup()
{
  input_subscriptions_.clear();  // before the session their callbacks feed goes
  debug_publishers_.clear();
  plugin_.stop();
#if !NAV2_PYIF_LYRICAL_API
  plan_.clear();
#endif
}

void PyController::sync_debug_publishers()
{
  auto node = node_.lock();
  if (!node || !plugin_.started()) {
    return;
  }
  const protocol::StringMap declared = session().debug_outputs();
  std::vector<std::string> wanted;
  for (const auto & [output, type] : declared) {
    auto found = debug_publishers_.find(output);
    if (found == debug_publishers_.end() || found->second.type != type) {
      debug_publishers_[output] = DebugPublisher{
        type, node->create_generic_publisher(name_ + "/" + output, type, rclcpp::QoS(1))};
      RCLCPP_INFO(
        bridge().ros_logger(), "%s: debug output on %s/%s (%s)", name_.c_str(), name_.c_str(),
        output.c_str(), type.c_str());
    }
    if (debug_publishers_[output].publisher->get_subscription_count() > 0) {
      wanted.push_back(output);
    }
  }
  session().set_debug_wanted(std::move(wanted));
}

void PyController::publish_debug()
{
  for (const protocol::DebugOutput & output : session().take_debug()) {
    const auto found = debug_publishers_.find(output.name);
    if (found == debug_publishers_.end() || found->second.type != output.type) {
      RCLCPP_WARN_ONCE(
        bridge().ros_logger(), "%s: the host returned debug output '%s' (%s), not declared at "
        "configure: dropped", name_.c_str(), output.name.c_str(), output.type.c_str());
      continue;
    }
    rclcpp::SerializedMessage message(output.cdr.size());
    rcl_serialized_message_t & raw = message.get_rcl_serialized_message();
    std::memcpy(raw.buffer, output.cdr.data(), output.cdr.size());
    raw.buffer_length = output.cdr.size();
    found->second.publisher->publish(message);
  }
}

void PyController::new_plan_begins()
{
  if (reset_owed_) {
    reset_owed_ = false;
    send_reset();
  }
  if (client::CarriedCycle * cycle = session().cycle()) {
    cycle->use_controller(session());  // the next goal checks prepare for this plan
  }
}

#if NAV2_PYIF_LYRICAL_API
void PyController::newPathReceived(const nav_msgs::msg::Path &)
{
  new_plan_begins();
}

geometry_msgs::msg::TwistStamped PyController::computeVelocityCommands(
  const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
  nav2_core::GoalChecker * goal_checker, const nav_msgs::msg::Path & transformed_global_plan,
  const geometry_msgs::msg::PoseStamped & global_goal)
{
  return bridge().forward(
    [&]() {
      // Already in the costmap's global frame (Nav2's path handler); the transform is a
      // no-op then, and keeps the protocol's one-frame rule should a handler differ.
      const std::string & frame = costmap_ros_->getGlobalFrameID();
      const auto tf_error = client::ErrorKind::ControllerTFError;
      const double tolerance = bridge().transform_tolerance();
      session().follow(
        ros::to_wire(transformed_global_plan),
        ros::to_wire(ros::in_frame(global_goal, frame, *tf_, tolerance, tf_error)));
      return command(pose, velocity, goal_checker);
    });
}
#else
void PyController::setPlan(const nav_msgs::msg::Path & path)
{
  bridge().forward(
    [&]() {
      new_plan_begins();
      const std::optional<client::CallError> deferred = session().set_plan(ros::to_wire(plan_.set(
        path, costmap_ros_->getGlobalFrameID(), *tf_, bridge().transform_tolerance())));
      if (deferred) {
        RCLCPP_WARN(
          bridge().ros_logger(), "%s: plan kept, sent when the host answers: %s", name_.c_str(),
          deferred->log_text().c_str());
      }
    });
}

geometry_msgs::msg::TwistStamped PyController::computeVelocityCommands(
  const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
  nav2_core::GoalChecker * goal_checker)
{
  return bridge().forward(
    [&]() {
      if (auto fresh = plan_.refreshed(
          costmap_ros_->getGlobalFrameID(), *tf_, bridge().transform_tolerance()))
      {
        // Localisation moved the plan's frame. A host failure leaves it owed, and the cycle
        // below sends it first (and fails as the host does).
        session().set_plan(ros::to_wire(*fresh));
      }
      return command(pose, velocity, goal_checker);
    });
}
#endif

geometry_msgs::msg::TwistStamped PyController::command(
  const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
  nav2_core::GoalChecker * goal_checker)
{
  const geometry_msgs::msg::PoseStamped global = ros::in_frame(
    pose, costmap_ros_->getGlobalFrameID(), *tf_, bridge().transform_tolerance(),
    client::ErrorKind::ControllerTFError);
  sync_debug_publishers();
  const protocol::PoseStamped wire_pose = ros::to_wire(global);
  const std::array<double, 6> wire_velocity = ros::to_wire(velocity);
  const std::optional<protocol::GoalChecker> wire_tolerances = ros::tolerances(goal_checker);
  try {
    // The command another call's query carried, when it was prepared for this call; else
    // the call on its own, carrying the goal check when Nav2 calls that last
    client::CarriedCycle * cycle = session().cycle();
    const protocol::TwistStamped cmd = cycle ?
      cycle->compute_velocity_commands(session(), wire_pose, wire_velocity, wire_tolerances) :
      session().compute_velocity_commands(wire_pose, wire_velocity, wire_tolerances).cmd_vel;
    host_silent_ = false;
    publish_debug();
    return ros::to_ros(cmd, costmap_ros_->getBaseFrameID(), pose.header.stamp);
  } catch (const client::CallError & error) {
    host_silent_ = error.cause() == client::Cause::TimedOut;
    throw;
  }
}

void PyController::setSpeedLimit(const double & speed_limit, const bool & percentage)
{
  try {
    session().set_speed_limit(speed_limit, percentage);
  } catch (const client::CallError & error) {
    RCLCPP_WARN(
      bridge().ros_logger(), "%s: speed limit %.3f%s: %s", name_.c_str(), speed_limit,
      percentage ? " %" : " m/s", error.log_text().c_str());
  }
}

#if NAV2_PYIF_JAZZY_API
bool PyController::cancel()
{
  try {
    return session().call(protocol::CancelRequest{}).cancelled;
  } catch (const client::CallError & error) {
    RCLCPP_WARN(bridge().ros_logger(), "%s: cancel: %s", name_.c_str(), error.what());
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
    session().call(protocol::ResetRequest{});
  } catch (const client::CallError & error) {
    RCLCPP_DEBUG(bridge().ros_logger(), "%s: reset: %s", name_.c_str(), error.what());
  }
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyController, nav2_core::Controller)
