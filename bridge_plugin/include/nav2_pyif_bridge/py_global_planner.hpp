// nav2_pyif_bridge::PyGlobalPlanner: a nav2_core::GlobalPlanner whose plans come from a Python
// planner in a planner host, over Zenoh, with Nav2's cancel checker forwarded (Jazzy+).
// The lifecycle is BridgedSession's.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry_msgs/msg/pose_stamped.hpp"
#include "nav2_core/global_planner.hpp"
#include "nav_msgs/msg/path.hpp"

#include "nav2_pyif_bridge/client/planner_session.hpp"
#include "nav2_pyif_bridge/bridged_session.hpp"

namespace nav2_pyif_bridge
{

class PyGlobalPlanner : public nav2_core::GlobalPlanner
{
public:
  void configure(
    const Nav2Node::WeakPtr & parent, std::string name, std::shared_ptr<TfBuffer> tf,
    std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros) override;
  void cleanup() override {plugin_.stop();}
  void activate() override {plugin_.activate();}
  void deactivate() override {plugin_.deactivate();}

  // Lyrical's viapoints travel in the costmap's global frame, as start and goal do; Jazzy's
  // cancel checker is polled while the plan is computed.
  nav_msgs::msg::Path createPlan(
    const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal
#if NAV2_PYIF_LYRICAL_API
    , const std::vector<geometry_msgs::msg::PoseStamped> & viapoints
#endif
#if NAV2_PYIF_JAZZY_API
    , std::function<bool()> cancel_checker
#endif
  ) override;

private:
  std::shared_ptr<TfBuffer> tf_;
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
  BridgedSession<client::PlannerSession> plugin_;
};

}  // namespace nav2_pyif_bridge
