// ROS messages and parameters <-> the protocol's types (PROTOCOL.md sections 6 and 13), and
// the frame changes the plugins make with the TF buffer.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "builtin_interfaces/msg/time.hpp"
#include "geometry_msgs/msg/pose_stamped.hpp"
#include "geometry_msgs/msg/transform_stamped.hpp"
#include "geometry_msgs/msg/twist.hpp"
#include "geometry_msgs/msg/twist_stamped.hpp"
#include "nav2_core/goal_checker.hpp"
#include "nav_msgs/msg/path.hpp"
#include "rclcpp/parameter_value.hpp"
#include "nav2_pyif_bridge/nav2_api.hpp"

#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::ros
{

std::int64_t to_ns(const builtin_interfaces::msg::Time & stamp) noexcept;
builtin_interfaces::msg::Time from_ns(std::int64_t ns) noexcept;

// A pose as the protocol's row (x, y, z, qx, qy, qz, qw) and back; a twist from its row.
std::array<double, 7> pose_row(const geometry_msgs::msg::Pose & pose) noexcept;
geometry_msgs::msg::Pose pose_of(const double * row) noexcept;
geometry_msgs::msg::Twist twist_of(const std::array<double, 6> & row) noexcept;

protocol::PoseStamped to_wire(const geometry_msgs::msg::PoseStamped & pose);
// The goal checker's tolerances, as the protocol carries them (std::nullopt without one).
std::optional<protocol::GoalChecker> tolerances(nav2_core::GoalChecker * goal_checker);
std::array<double, 6> to_wire(const geometry_msgs::msg::Twist & twist) noexcept;
// The plan's header frame and stamp, and every pose (their own headers are not sent).
protocol::Path to_wire(const nav_msgs::msg::Path & path);

// Empty frame / zero stamp in the wire message: `frame` / `stamp` instead.
geometry_msgs::msg::TwistStamped to_ros(
  const protocol::TwistStamped & cmd, const std::string & frame,
  const builtin_interfaces::msg::Time & stamp);
nav_msgs::msg::Path to_ros(
  const protocol::Path & path, const std::string & frame,
  const builtin_interfaces::msg::Time & stamp);

// NOT_SET gives std::nullopt; byte arrays travel as int arrays.
std::optional<protocol::ParamValue> to_wire(const rclcpp::ParameterValue & value);
rclcpp::ParameterValue to_ros(const protocol::ParamValue & value);

// The latest transform `from` -> `frame`. Throws client::CallError of `tf_error`
// (ControllerTFError / PlannerTFError) naming `what` and the frames.
geometry_msgs::msg::TransformStamped latest_transform(
  const std::string & frame, const std::string & from, TfBuffer & tf, double timeout_s,
  client::ErrorKind tf_error, const std::string & what);

// `pose` in `frame`, with the latest transform (unchanged when already in it). The plan's own
// frame change is FreshPlan's.
geometry_msgs::msg::PoseStamped in_frame(
  const geometry_msgs::msg::PoseStamped & pose, const std::string & frame,
  TfBuffer & tf, double timeout_s, client::ErrorKind tf_error);

}  // namespace nav2_pyif_bridge::ros
