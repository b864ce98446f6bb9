#include "nav2_pyif_bridge/ros_conversions.hpp"

#include <limits>
#include <utility>
#include <variant>
#include <vector>

#include "nav2_pyif_bridge/tf2_headers.hpp"

namespace nav2_pyif_bridge::ros
{
namespace proto = protocol;

std::int64_t to_ns(const builtin_interfaces::msg::Time & stamp) noexcept
{
  return static_cast<std::int64_t>(stamp.sec) * 1000000000LL + stamp.nanosec;
}

builtin_interfaces::msg::Time from_ns(std::int64_t ns) noexcept
{
  builtin_interfaces::msg::Time stamp;
  std::int64_t sec = ns / 1000000000LL;
  std::int64_t rest = ns % 1000000000LL;
  if (rest < 0) {
    rest += 1000000000LL;
    sec -= 1;
  }
  stamp.sec = static_cast<std::int32_t>(sec);
  stamp.nanosec = static_cast<std::uint32_t>(rest);
  return stamp;
}

std::array<double, 7> pose_row(const geometry_msgs::msg::Pose & p) noexcept
{
  return {p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
    p.orientation.z, p.orientation.w};
}

geometry_msgs::msg::Pose pose_of(const double * row) noexcept
{
  geometry_msgs::msg::Pose p;
  p.position.x = row[0];
  p.position.y = row[1];
  p.position.z = row[2];
  p.orientation.x = row[3];
  p.orientation.y = row[4];
  p.orientation.z = row[5];
  p.orientation.w = row[6];
  return p;
}

geometry_msgs::msg::Twist twist_of(const std::array<double, 6> & row) noexcept
{
  geometry_msgs::msg::Twist t;
  t.linear.x = row[0];
  t.linear.y = row[1];
  t.linear.z = row[2];
  t.angular.x = row[3];
  t.angular.y = row[4];
  t.angular.z = row[5];
  return t;
}

proto::PoseStamped to_wire(const geometry_msgs::msg::PoseStamped & pose)
{
  return proto::PoseStamped{pose.header.frame_id, to_ns(pose.header.stamp), pose_row(pose.pose)};
}

std::array<double, 6> to_wire(const geometry_msgs::msg::Twist & t) noexcept
{
  return {t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z};
}

proto::Path to_wire(const nav_msgs::msg::Path & path)
{
  proto::Path out;
  out.frame_id = path.header.frame_id;
  out.stamp_ns = to_ns(path.header.stamp);
  out.poses.reserve(path.poses.size() * proto::kPoseRowSize);
  for (const auto & pose : path.poses) {
    const auto row = pose_row(pose.pose);
    out.poses.insert(out.poses.end(), row.begin(), row.end());
  }
  return out;
}

geometry_msgs::msg::TwistStamped to_ros(
  const proto::TwistStamped & cmd, const std::string & frame,
  const builtin_interfaces::msg::Time & stamp)
{
  geometry_msgs::msg::TwistStamped out;
  out.header.frame_id = cmd.frame_id.empty() ? frame : cmd.frame_id;
  out.header.stamp = cmd.stamp_ns == 0 ? stamp : from_ns(cmd.stamp_ns);
  out.twist = twist_of(cmd.twist);
  return out;
}

nav_msgs::msg::Path to_ros(
  const proto::Path & path, const std::string & frame,
  const builtin_interfaces::msg::Time & stamp)
{
  nav_msgs::msg::Path out;
  out.header.frame_id = path.frame_id.empty() ? frame : path.frame_id;
  out.header.stamp = path.stamp_ns == 0 ? stamp : from_ns(path.stamp_ns);
  out.poses.resize(path.pose_count());
  for (std::size_t i = 0; i < out.poses.size(); ++i) {
    out.poses[i].header = out.header;
    out.poses[i].pose = pose_of(&path.poses[i * proto::kPoseRowSize]);
  }
  return out;
}

std::optional<proto::ParamValue> to_wire(const rclcpp::ParameterValue & value)
{
  switch (value.get_type()) {
    case rclcpp::ParameterType::PARAMETER_BOOL:
      return proto::ParamValue{value.get<bool>()};
    case rclcpp::ParameterType::PARAMETER_INTEGER:
      return proto::ParamValue{std::int64_t{value.get<std::int64_t>()}};
    case rclcpp::ParameterType::PARAMETER_DOUBLE:
      return proto::ParamValue{value.get<double>()};
    case rclcpp::ParameterType::PARAMETER_STRING:
      return proto::ParamValue{value.get<std::string>()};
    case rclcpp::ParameterType::PARAMETER_BYTE_ARRAY: {
        std::vector<std::int64_t> ints;
        for (const auto byte : value.get<std::vector<std::uint8_t>>()) {
          ints.push_back(byte);
        }
        return proto::ParamValue{std::move(ints)};
      }
    case rclcpp::ParameterType::PARAMETER_BOOL_ARRAY:
      return proto::ParamValue{value.get<std::vector<bool>>()};
    case rclcpp::ParameterType::PARAMETER_INTEGER_ARRAY:
      return proto::ParamValue{value.get<std::vector<std::int64_t>>()};
    case rclcpp::ParameterType::PARAMETER_DOUBLE_ARRAY:
      return proto::ParamValue{value.get<std::vector<double>>()};
    case rclcpp::ParameterType::PARAMETER_STRING_ARRAY:
      return proto::ParamValue{value.get<std::vector<std::string>>()};
    default:
      return std::nullopt;
  }
}

rclcpp::ParameterValue to_ros(const proto::ParamValue & value)
{
  return std::visit([](const auto & v) {return rclcpp::ParameterValue(v);}, value);
}

geometry_msgs::msg::TransformStamped latest_transform(
  const std::string & frame, const std::string & from, TfBuffer & tf, double timeout_s,
  client::ErrorKind tf_error, const std::string & what)
{
  try {
    return tf.lookupTransform(frame, from, tf2::TimePointZero, tf2::durationFromSec(timeout_s));
  } catch (const tf2::TransformException & error) {
    throw client::CallError(
            tf_error, client::Cause::Local,
            "cannot transform " + what + " from " + from + " to " + frame + ": " + error.what());
  }
}

geometry_msgs::msg::PoseStamped in_frame(
  const geometry_msgs::msg::PoseStamped & pose, const std::string & frame,
  TfBuffer & tf, double timeout_s, client::ErrorKind tf_error)
{
  if (pose.header.frame_id == frame || pose.header.frame_id.empty()) {
    return pose;
  }
  geometry_msgs::msg::PoseStamped out;
  tf2::doTransform(
    pose, out,
    latest_transform(frame, pose.header.frame_id, tf, timeout_s, tf_error, "a pose"));
  return out;
}

std::optional<proto::GoalChecker> tolerances(nav2_core::GoalChecker * goal_checker)
{
  if (goal_checker == nullptr) {
    return std::nullopt;
  }
  geometry_msgs::msg::Pose pose_tolerance;
  geometry_msgs::msg::Twist velocity_tolerance;
#if NAV2_PYIF_LYRICAL_API
  double path_length_tolerance = std::numeric_limits<double>::lowest();
  if (!goal_checker->getTolerances(pose_tolerance, velocity_tolerance, path_length_tolerance)) {
    return std::nullopt;
  }
#else
  if (!goal_checker->getTolerances(pose_tolerance, velocity_tolerance)) {
    return std::nullopt;
  }
#endif
  proto::GoalChecker wire{
    pose_tolerance.position.x, tf2::getYaw(pose_tolerance.orientation),
    velocity_tolerance.linear.x, velocity_tolerance.angular.z, std::nullopt};
#if NAV2_PYIF_LYRICAL_API
  // Nav2 marks a tolerance the checker does not measure with lowest()
  if (path_length_tolerance != std::numeric_limits<double>::lowest()) {
    wire.path_length_tolerance = path_length_tolerance;
  }
#endif
  return wire;
}

}  // namespace nav2_pyif_bridge::ros
