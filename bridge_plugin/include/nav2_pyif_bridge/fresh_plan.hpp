// The plan Nav2 gave, kept in its own frame, and the transform it was sent to the host with.
// Nav2's own controllers re-transform their plan every cycle: when localisation corrects
// map -> odom (AMCL jumps of 10-30 cm), a plan transformed once at setPlan is stale. This
// re-transforms it when that transform has moved, so the plan is re-sent only then.
#pragma once

#include <optional>
#include <string>

#include "geometry_msgs/msg/transform.hpp"
#include "nav_msgs/msg/path.hpp"
#include "nav2_pyif_bridge/nav2_api.hpp"

namespace nav2_pyif_bridge
{

class FreshPlan
{
public:
  // A move of the plan's frame below both thresholds is not worth a re-send.
  explicit FreshPlan(double min_translation_m = 0.01, double min_rotation_rad = 0.005)
  : min_translation_m_(min_translation_m), min_rotation_rad_(min_rotation_rad) {}

  // Nav2's new plan: returns it in `frame`, to send. Throws client::CallError
  // (ControllerTFError) when it cannot be transformed.
  nav_msgs::msg::Path set(
    const nav_msgs::msg::Path & path, const std::string & frame, TfBuffer & tf,
    double timeout_s);

  // The plan in `frame` again when its frame has moved since it was last sent, else nothing.
  std::optional<nav_msgs::msg::Path> refreshed(
    const std::string & frame, TfBuffer & tf, double timeout_s);

  void clear() {plan_.reset();}

private:
  nav_msgs::msg::Path transformed(const geometry_msgs::msg::Transform & transform,
    const std::string & frame);
  bool moved(const geometry_msgs::msg::Transform & now) const;

  double min_translation_m_;
  double min_rotation_rad_;
  std::optional<nav_msgs::msg::Path> plan_;  // as Nav2 gave it
  geometry_msgs::msg::Transform sent_with_;  // plan frame -> costmap frame, when last sent
};

}  // namespace nav2_pyif_bridge
