// nav2_pyif_bridge::PyPathHandler (Lyrical only): a nav2_core::PathHandler whose choice of the
// plan's part to follow each cycle is a Python path handler's, in a planner host, over Zenoh
// (PROTOCOL.md section 19). Thin: the plan goes to the host once per plan; each cycle the host
// answers which poses [start, end) of it the controller follows; the frames stay here.
//
// Which calls go to Python, from controller_server's cycle (isGoalReached, check,
// getTransformedGoal, findPlanSegment, transformLocalPlan, computeVelocityCommands):
//   setPlan            -> set_plan (the plan in its own frame), once per new plan
//   findPlanSegment    -> find_plan_segment (the robot in the plan's frame); with a Python goal
//                         or progress checker in the same controller_server its query is
//                         carried by theirs (carried_cycle.hpp): no round trip of its own
//   transformLocalPlan -> none: the segment's poses into the costmap's frame, cut at the
//                         costmap's edge, as Nav2's FeasiblePathHandler does
//   getTransformedGoal -> none: the plan's last pose in the costmap's frame
#pragma once

#include "nav2_pyif_bridge/nav2_api.hpp"

#if NAV2_PYIF_LYRICAL_API

#include <memory>
#include <string>

#include "nav2_core/path_handler.hpp"
#include "nav2_costmap_2d/costmap_2d_ros.hpp"
#include "nav_msgs/msg/path.hpp"

#include "nav2_pyif_bridge/bridged_session.hpp"
#include "nav2_pyif_bridge/client/path_handler_session.hpp"

namespace nav2_pyif_bridge
{

class PyPathHandler : public nav2_core::PathHandler
{
public:
  void initialize(
    const Nav2Node::WeakPtr & parent, const rclcpp::Logger & logger,
    const std::string & plugin_name,
    const std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros,
    TfBuffer::SharedPtr tf) override;
  // A failure of the host is logged and the plan sent with the next segment (as the
  // controller's plan); the planner's own error throws.
  void setPlan(const nav_msgs::msg::Path & path) override;
  nav2_core::PathSegment findPlanSegment(const geometry_msgs::msg::PoseStamped & pose) override;
  nav_msgs::msg::Path transformLocalPlan(
    const nav2_core::PathIterator & closest_point,
    const nav2_core::PathIterator & pruned_plan_end) override;
  geometry_msgs::msg::PoseStamped getTransformedGoal(
    const builtin_interfaces::msg::Time & stamp) override;

private:
  // The plan's frame (the costmap's global frame for a plan without one).
  std::string plan_frame() const;
  geometry_msgs::msg::PoseStamped in_plan_frame(const geometry_msgs::msg::PoseStamped & pose);

  std::string name_;
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
  TfBuffer::SharedPtr tf_;
  BridgedSession<client::PathHandlerSession> plugin_;
  nav_msgs::msg::Path plan_;  // as Nav2 gave it: the segments' iterators point into it
  builtin_interfaces::msg::Time stamp_;  // the robot pose's of the latest segment
};

}  // namespace nav2_pyif_bridge

#endif  // NAV2_PYIF_LYRICAL_API
