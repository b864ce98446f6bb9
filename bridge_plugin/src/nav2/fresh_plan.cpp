#include "nav2_pyif_bridge/fresh_plan.hpp"

#include <cmath>

#include "nav2_pyif_bridge/tf2_headers.hpp"

#include "nav2_pyif_bridge/client/error_mapping.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{

namespace
{

geometry_msgs::msg::Transform lookup(
  const std::string & frame, const std::string & from, TfBuffer & tf, double timeout_s)
{
  return ros::latest_transform(
    frame, from, tf, timeout_s, client::ErrorKind::ControllerTFError, "the plan").transform;
}

bool in_frame_already(const nav_msgs::msg::Path & path, const std::string & frame)
{
  return path.header.frame_id == frame || path.header.frame_id.empty();
}

}  // namespace

nav_msgs::msg::Path FreshPlan::set(
  const nav_msgs::msg::Path & path, const std::string & frame, TfBuffer & tf,
  double timeout_s)
{
  plan_ = path;
  if (in_frame_already(path, frame)) {
    return path;
  }
  return transformed(lookup(frame, path.header.frame_id, tf, timeout_s), frame);
}

std::optional<nav_msgs::msg::Path> FreshPlan::refreshed(
  const std::string & frame, TfBuffer & tf, double timeout_s)
{
  if (!plan_ || in_frame_already(*plan_, frame)) {
    return std::nullopt;
  }
  const geometry_msgs::msg::Transform now = lookup(frame, plan_->header.frame_id, tf, timeout_s);
  if (!moved(now)) {
    return std::nullopt;
  }
  return transformed(now, frame);
}

nav_msgs::msg::Path FreshPlan::transformed(
  const geometry_msgs::msg::Transform & transform, const std::string & frame)
{
  geometry_msgs::msg::TransformStamped stamped;
  stamped.transform = transform;
  nav_msgs::msg::Path out;
  out.header.frame_id = frame;
  out.header.stamp = plan_->header.stamp;
  out.poses.resize(plan_->poses.size());
  for (std::size_t i = 0; i < plan_->poses.size(); ++i) {
    tf2::doTransform(plan_->poses[i].pose, out.poses[i].pose, stamped);
    out.poses[i].header = out.header;
  }
  sent_with_ = transform;
  return out;
}

bool FreshPlan::moved(const geometry_msgs::msg::Transform & now) const
{
  const double dx = now.translation.x - sent_with_.translation.x;
  const double dy = now.translation.y - sent_with_.translation.y;
  const double dz = now.translation.z - sent_with_.translation.z;
  tf2::Quaternion before, after;
  tf2::fromMsg(sent_with_.rotation, before);
  tf2::fromMsg(now.rotation, after);
  return std::sqrt(dx * dx + dy * dy + dz * dz) >= min_translation_m_ ||
         std::abs(before.angleShortestPath(after)) >= min_rotation_rad_;
}

}  // namespace nav2_pyif_bridge
