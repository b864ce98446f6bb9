// nav2_pyif_bridge::PyGlobalPlanner: a nav2_core::GlobalPlanner whose plans come from a Python
// planner in a planner host, over Zenoh, with Nav2's cancel checker forwarded (Jazzy+).
// The lifecycle is PyPlugin's.
#pragma once

#include <functional>
#include <vector>

#include "geometry_msgs/msg/pose_stamped.hpp"
#include "nav2_core/global_planner.hpp"
#include "nav_msgs/msg/path.hpp"

#include "nav2_pyif_bridge/client/planner_session.hpp"
#include "nav2_pyif_bridge/py_plugin.hpp"

namespace nav2_pyif_bridge
{

class PyGlobalPlanner : public PyPlugin<nav2_core::GlobalPlanner, client::PlannerSession>
{
public:
#if NAV2_PYIF_LYRICAL_API
  // The viapoints travel in the costmap's global frame, as start and goal do.
  nav_msgs::msg::Path createPlan(
    const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
    const std::vector<geometry_msgs::msg::PoseStamped> & viapoints,
    std::function<bool()> cancel_checker) override;
#elif NAV2_PYIF_JAZZY_API
  nav_msgs::msg::Path createPlan(
    const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
    std::function<bool()> cancel_checker) override;
#else
  nav_msgs::msg::Path createPlan(
    const geometry_msgs::msg::PoseStamped & start,
    const geometry_msgs::msg::PoseStamped & goal) override;
#endif

private:
  nav_msgs::msg::Path plan(
    const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal,
    const std::vector<geometry_msgs::msg::PoseStamped> & viapoints,
    const std::function<bool()> & cancel_checker);
};

}  // namespace nav2_pyif_bridge
