#include "nav2_pyif_bridge/py_behavior.hpp"

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

#include "nav2_util/robot_utils.hpp"
#include "pluginlib/class_list_macros.hpp"

#include "nav2_pyif_bridge/costmap_subscriber_source.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{
namespace
{

using client::BehaviorFailure;
using client::BehaviorStatus;
using nav2_behaviors::ResultStatus;
using nav2_behaviors::Status;

// Goal fields and result codes that only some distributions' actions have.
template<class Goal, class = void>
struct HasDisableCollisionChecks : std::false_type {};
template<class Goal>
struct HasDisableCollisionChecks<Goal, std::void_t<decltype(Goal::disable_collision_checks)>>
  : std::true_type {};

template<class Result, class = void>
struct InvalidInputCode
{
  static constexpr std::uint16_t value = Result::UNKNOWN;  // Spin has none
};
template<class Result>
struct InvalidInputCode<Result, std::void_t<decltype(Result::INVALID_INPUT)>>
{
  static constexpr std::uint16_t value = Result::INVALID_INPUT;
};

template<class Goal>
void add_common(protocol::Params & out, const Goal & goal)
{
  out.set("time_allowance", rclcpp::Duration(goal.time_allowance).seconds());
  if constexpr (HasDisableCollisionChecks<Goal>::value) {
    out.set("disable_collision_checks", static_cast<bool>(goal.disable_collision_checks));
  } else {
    out.set("disable_collision_checks", false);
  }
}

double number(const protocol::Params & params, const char * name, double fallback)
{
  const auto * value = params.find(name);
  if (!value) {
    return fallback;
  }
  if (const auto * d = std::get_if<double>(value)) {
    return *d;
  }
  if (const auto * i = std::get_if<std::int64_t>(value)) {
    return static_cast<double>(*i);
  }
  return fallback;
}

template<class Result>
std::uint16_t error_code(BehaviorFailure failure)
{
  switch (failure) {
    case BehaviorFailure::None:
      return Result::NONE;
    case BehaviorFailure::Timeout:
      return Result::TIMEOUT;
    case BehaviorFailure::TfError:
      return Result::TF_ERROR;
    case BehaviorFailure::InvalidInput:
      return InvalidInputCode<Result>::value;
    case BehaviorFailure::CollisionAhead:
      return Result::COLLISION_AHEAD;
    default:
      return Result::UNKNOWN;
  }
}

// TimedBehavior's ResultStatus; Lyrical's also carries a message for the action's result.
ResultStatus result_status(Status status, std::uint16_t code, const std::string & message = {})
{
  ResultStatus result{};
  result.status = status;
  result.error_code = code;
#if NAV2_PYIF_LYRICAL_API
  result.error_msg = message;
#else
  static_cast<void>(message);
#endif
  return result;
}

}  // namespace

protocol::Params BehaviorAction<nav2_msgs::action::BackUp>::fields(
  const nav2_msgs::action::BackUp::Goal & goal)
{
  protocol::Params out;
  out.set("target_x", goal.target.x);
  out.set("target_y", goal.target.y);
  out.set("target_z", goal.target.z);
  out.set("speed", static_cast<double>(goal.speed));
  add_common(out, goal);
  return out;
}

void BehaviorAction<nav2_msgs::action::BackUp>::feedback(
  nav2_msgs::action::BackUp::Feedback & out, const protocol::Params & in)
{
  out.distance_traveled =
    static_cast<float>(number(in, "distance_traveled", out.distance_traveled));
}

protocol::Params BehaviorAction<nav2_msgs::action::Spin>::fields(
  const nav2_msgs::action::Spin::Goal & goal)
{
  protocol::Params out;
  out.set("target_yaw", static_cast<double>(goal.target_yaw));
  add_common(out, goal);
  return out;
}

void BehaviorAction<nav2_msgs::action::Spin>::feedback(
  nav2_msgs::action::Spin::Feedback & out, const protocol::Params & in)
{
  out.angular_distance_traveled = static_cast<float>(
    number(in, "angular_distance_traveled", out.angular_distance_traveled));
}

template<class ActionT>
void PyBehavior<ActionT>::onConfigure()
{
  auto node = this->node_.lock();
  // Jazzy's costmap subscribers take nav2_util::LifecycleNode (Lyrical's the nav2::LifecycleNode
  // the behaviour already has).
#if NAV2_PYIF_LYRICAL_API
  using BehaviorNode = nav2::LifecycleNode;
#else
  using BehaviorNode = nav2_util::LifecycleNode;
#endif
  auto nav2_node = std::dynamic_pointer_cast<BehaviorNode>(node);
  if (!nav2_node) {
    throw std::runtime_error(
      "nav2_pyif_bridge: " + this->behavior_name_ + ": behavior_server's node is not a Nav2 "
      "LifecycleNode");
  }
  // behavior_server's own topics (its subscriptions for the collision checker are its own).
  auto topic = [&](const char * name, const char * fallback) {
      return node->has_parameter(name) ? node->get_parameter(name).as_string() :
             std::string(fallback);
    };
  costmap_sub_ = std::make_shared<nav2_costmap_2d::CostmapSubscriber>(
    nav2_node, topic("local_costmap_topic", "local_costmap/costmap_raw"));
  footprint_sub_ = std::make_shared<nav2_costmap_2d::FootprintSubscriber>(
    nav2_node, topic("local_footprint_topic", "local_costmap/published_footprint"), *this->tf_,
    this->robot_base_frame_, this->transform_tolerance_);
  CostmapBinding costmap;
  costmap.global_frame = this->local_frame_;
  costmap.robot_base_frame = this->robot_base_frame_;
  costmap.transform_tolerance = this->transform_tolerance_;
  costmap.source = std::make_unique<CostmapSubscriberSource>(
    costmap_sub_, this->local_frame_, footprint_sub_);
  plugin_.start(this->node_, this->behavior_name_, std::move(costmap));
  feedback_ = std::make_shared<typename ActionT::Feedback>();
}

template<class ActionT>
void PyBehavior<ActionT>::onCleanup()
{
  plugin_.stop();
  costmap_sub_.reset();
  footprint_sub_.reset();
}

template<class ActionT>
void PyBehavior<ActionT>::activate()
{
  nav2_behaviors::TimedBehavior<ActionT>::activate();
  plugin_.activate();
}

template<class ActionT>
void PyBehavior<ActionT>::deactivate()
{
  nav2_behaviors::TimedBehavior<ActionT>::deactivate();
  plugin_.deactivate();
}

template<class ActionT>
bool PyBehavior<ActionT>::robot_pose(geometry_msgs::msg::PoseStamped & pose) const
{
  return nav2_util::getCurrentPose(
    pose, *this->tf_, this->local_frame_, this->robot_base_frame_, this->transform_tolerance_);
}

template<class ActionT>
ResultStatus PyBehavior<ActionT>::result_of(const client::BehaviorStep & step, const char * hook)
{
  if (!step.error.empty()) {
    RCLCPP_ERROR(
      this->logger_, "%s: %s failed: %s", this->behavior_name_.c_str(), hook,
      step.error.c_str());
  }
  switch (step.status) {
    case BehaviorStatus::Succeeded:
      return result_status(Status::SUCCEEDED, Result::NONE);
    case BehaviorStatus::Running:
      return result_status(Status::RUNNING, Result::NONE);
    default:
      return result_status(Status::FAILED, error_code<Result>(step.failure), step.error);
  }
}

template<class ActionT>
ResultStatus PyBehavior<ActionT>::onRun(
  const std::shared_ptr<const typename ActionT::Goal> command)
{
  geometry_msgs::msg::PoseStamped pose;
  if (!robot_pose(pose)) {
    RCLCPP_ERROR(this->logger_, "Initial robot pose is not available.");
    return result_status(Status::FAILED, Result::TF_ERROR, "Initial robot pose is not available.");
  }
  start_ = this->clock_->now();
  outcome_ = "cancelled";
  *feedback_ = typename ActionT::Feedback();
  const client::BehaviorStep step = plugin_.session().run(
    BehaviorAction<ActionT>::kName, BehaviorAction<ActionT>::fields(*command),
    ros::to_wire(pose));
  return result_of(step, "on_run");
}

template<class ActionT>
ResultStatus PyBehavior<ActionT>::onCycleUpdate()
{
  geometry_msgs::msg::PoseStamped pose;
  if (!robot_pose(pose)) {
    this->stopRobot();
    RCLCPP_ERROR(this->logger_, "Current robot pose is not available.");
    outcome_ = "failed";
    return result_status(Status::FAILED, Result::TF_ERROR, "Current robot pose is not available.");
  }
  const double elapsed = (this->clock_->now() - start_).seconds();
  const client::BehaviorStep step = plugin_.session().cycle_update(ros::to_wire(pose), elapsed);
  if (!step.feedback.empty()) {
    BehaviorAction<ActionT>::feedback(*feedback_, step.feedback);
    this->action_server_->publish_feedback(feedback_);
  }
  if (step.status == BehaviorStatus::Running) {
    if (step.cmd_vel) {
      auto cmd = std::make_unique<geometry_msgs::msg::TwistStamped>(
        ros::to_ros(*step.cmd_vel, this->robot_base_frame_, this->clock_->now()));
      this->vel_pub_->publish(std::move(cmd));
    }
  } else {
    this->stopRobot();  // as Nav2's behaviours do when they end
    outcome_ = step.status == BehaviorStatus::Succeeded ? "succeeded" : "failed";
  }
  return result_of(step, "on_cycle_update");
}

template<class ActionT>
void PyBehavior<ActionT>::onActionCompletion(std::shared_ptr<Result> result)
{
  const double elapsed =
    result ? rclcpp::Duration(result->total_elapsed_time).seconds() :
    (this->clock_->now() - start_).seconds();
  plugin_.session().action_completion(outcome_, elapsed);
}

template class PyBehavior<nav2_msgs::action::BackUp>;
template class PyBehavior<nav2_msgs::action::Spin>;

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyBackUp, nav2_core::Behavior)
PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PySpin, nav2_core::Behavior)
