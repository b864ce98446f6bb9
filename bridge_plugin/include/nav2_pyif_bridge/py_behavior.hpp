// nav2_pyif_bridge::PyBackUp and PySpin: behavior_server plugins (nav2_core::Behavior, run by
// nav2_behaviors::TimedBehavior) whose behaviour is a Python Behavior in a planner host, over
// Zenoh. TimedBehavior keeps what it does for Nav2's own behaviours: the action server named
// after the plugin (the BT's BackUp and Spin nodes call it), the cycle at cycle_frequency,
// cancel, stopping the robot and publishing cmd_vel. This class only forwards each of its
// hooks (onRun, onCycleUpdate, onActionCompletion) to the session, with the robot pose in
// behavior_server's local_frame and the local costmap and footprint of its topics.
//
// A behaviour never throws into behavior_server: a failed call (no host, no reply in time, a
// Python exception, a non-finite command) ends the action as FAILED with the action's UNKNOWN
// error code, the robot stopped and the traceback in the log (client/behavior_session.hpp).
//
// Built against Nav2 Jazzy, Kilted and Lyrical (TimedBehavior's ResultStatus, two collision
// checkers, getResourceInfo; Lyrical's node and TF types and its result message); CMake
// leaves it out on Humble, whose TimedBehavior differs.
#pragma once

#include <memory>
#include <string>

#include "nav2_behaviors/timed_behavior.hpp"
#include "nav2_costmap_2d/costmap_subscriber.hpp"
#include "nav2_costmap_2d/footprint_subscriber.hpp"
#include "nav2_msgs/action/back_up.hpp"
#include "nav2_msgs/action/spin.hpp"

#include "nav2_pyif_bridge/bridged_session.hpp"
#include "nav2_pyif_bridge/client/behavior_session.hpp"

namespace nav2_pyif_bridge
{

// What differs per action: its type name, its goal's fields as plain values, its feedback.
template<class ActionT>
struct BehaviorAction;

template<>
struct BehaviorAction<nav2_msgs::action::BackUp>
{
  static constexpr const char * kName = "nav2_msgs/action/BackUp";
  // target_x, target_y, target_z [m], speed [m/s], time_allowance [s],
  // disable_collision_checks (where the goal has it)
  static protocol::Params fields(const nav2_msgs::action::BackUp::Goal & goal);
  // distance_traveled [m]
  static void feedback(nav2_msgs::action::BackUp::Feedback & out, const protocol::Params & in);
};

template<>
struct BehaviorAction<nav2_msgs::action::Spin>
{
  static constexpr const char * kName = "nav2_msgs/action/Spin";
  // target_yaw [rad], time_allowance [s], disable_collision_checks (where the goal has it)
  static protocol::Params fields(const nav2_msgs::action::Spin::Goal & goal);
  // angular_distance_traveled [rad]
  static void feedback(nav2_msgs::action::Spin::Feedback & out, const protocol::Params & in);
};

template<class ActionT>
class PyBehavior : public nav2_behaviors::TimedBehavior<ActionT>
{
public:
  using Result = typename ActionT::Result;

  nav2_behaviors::ResultStatus onRun(
    const std::shared_ptr<const typename ActionT::Goal> command) override;
  nav2_behaviors::ResultStatus onCycleUpdate() override;
  void onConfigure() override;
  void onCleanup() override;
  void onActionCompletion(std::shared_ptr<Result> result) override;
  void activate() override;
  void deactivate() override;
  // The local costmap: behavior_server then subscribes to it for its collision checker too.
  nav2_core::CostmapInfoType getResourceInfo() override
  {
    return nav2_core::CostmapInfoType::LOCAL;
  }

private:
  // The robot in behavior_server's local_frame; false when TF has no transform.
  bool robot_pose(geometry_msgs::msg::PoseStamped & pose) const;
  // The step as TimedBehavior's ResultStatus (the failure as the action's error code); a
  // failed call's log text goes to the log.
  nav2_behaviors::ResultStatus result_of(const client::BehaviorStep & step, const char * hook);

  BridgedSession<client::BehaviorSession> plugin_;
  std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> costmap_sub_;
  std::shared_ptr<nav2_costmap_2d::FootprintSubscriber> footprint_sub_;
  typename ActionT::Feedback::SharedPtr feedback_;
  rclcpp::Time start_;
  std::string outcome_{"cancelled"};  // how the action ended, for onActionCompletion
};

// The plugin classes named in nav2_pyif_bridge_plugins.xml.
class PyBackUp : public PyBehavior<nav2_msgs::action::BackUp> {};
class PySpin : public PyBehavior<nav2_msgs::action::Spin> {};

}  // namespace nav2_pyif_bridge
