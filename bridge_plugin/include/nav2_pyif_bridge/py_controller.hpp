// nav2_pyif_bridge::PyController: a nav2_core::Controller whose every call is answered by a
// Python controller in a planner host, over Zenoh. Thin: frames and messages here, the
// lifecycle in BridgedSession, the rest in client::ControllerSession and PluginBridge.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry_msgs/msg/pose_stamped.hpp"
#include "geometry_msgs/msg/twist.hpp"
#include "geometry_msgs/msg/twist_stamped.hpp"
#include "nav2_core/controller.hpp"
#include "nav2_core/goal_checker.hpp"
#include "nav_msgs/msg/path.hpp"
#include "rclcpp/generic_publisher.hpp"
#include "rclcpp/generic_subscription.hpp"

#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/fresh_plan.hpp"
#include "nav2_pyif_bridge/bridged_session.hpp"

namespace nav2_pyif_bridge
{

class PyController : public nav2_core::Controller
{
public:
  // Also subscribes to the `inputs` topics (their serialized messages go to the host as they
  // are: no per-type code here).
  void configure(
    const Nav2Node::WeakPtr & parent, std::string name,
    std::shared_ptr<TfBuffer> tf,
    std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros) override;
  // Also forgets the plan, the subscriptions and the debug publishers.
  void cleanup() override;
  void activate() override {plugin_.activate();}
  void deactivate() override {plugin_.deactivate();}

#if NAV2_PYIF_LYRICAL_API
  // A new global plan: the goal checks that follow prepare for it. Nothing is sent: the host
  // gets the plan controller_server transforms for each cycle, with that cycle.
  void newPathReceived(const nav_msgs::msg::Path & raw_global_path) override;
  // The host's command (as below), the transformed plan and the global goal carried along
  // when they changed since the host last got them (ControllerSession::follow).
  geometry_msgs::msg::TwistStamped computeVelocityCommands(
    const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
    nav2_core::GoalChecker * goal_checker, const nav_msgs::msg::Path & transformed_global_plan,
    const geometry_msgs::msg::PoseStamped & global_goal) override;
#else
  // The plan, transformed into the costmap's global frame (ControllerTFError when it cannot be);
  // re-sent, transformed anew, before a cycle in which that transform has moved.
  void setPlan(const nav_msgs::msg::Path & path) override;
  // The host's command, every component finite; else the nav2_core exception it named, or
  // ControllerTimedOut / ControllerException (Humble: PlannerException). Never a made-up twist.
  geometry_msgs::msg::TwistStamped computeVelocityCommands(
    const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
    nav2_core::GoalChecker * goal_checker) override;
#endif
  // Called from a subscription: logs instead of throwing; the limit reaches the next host.
  void setSpeedLimit(const double & speed_limit, const bool & percentage) override;

#if NAV2_PYIF_JAZZY_API
  // True when the host says the controller finished cancelling, or when no host answers
  // (nothing left to cancel there; Nav2 stops the robot).
  bool cancel() override;
  // Never throws (Nav2 calls it after every goal).
  void reset() override;
#endif

private:
  // The cycle's call, once the host has the plan this cycle follows.
  geometry_msgs::msg::TwistStamped command(
    const geometry_msgs::msg::PoseStamped & pose, const geometry_msgs::msg::Twist & velocity,
    nav2_core::GoalChecker * goal_checker);
  // The reset Nav2's last reset() left owed, sent before the next plan; and the carried
  // cycle's goal checks prepared for the new plan.
  void new_plan_begins();
  void send_reset();  // the session's reset; a failure is only logged (debug)
  // A publisher <plugin name>/<output> per debug output the served planner declares (it may
  // be known only once a host answered, and change with a hot swap), and which of them have
  // a subscriber now: the host builds only those.
  void sync_debug_publishers();
  void publish_debug();

  client::ControllerSession & session() {return plugin_.session();}
  PluginBridge & bridge() {return plugin_.bridge();}

  std::string name_;
  std::shared_ptr<TfBuffer> tf_;
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
  BridgedSession<client::ControllerSession> plugin_;
  Nav2Node::WeakPtr node_;
  std::vector<rclcpp::GenericSubscription::SharedPtr> input_subscriptions_;
  struct DebugPublisher
  {
    std::string type;
    rclcpp::GenericPublisher::SharedPtr publisher;
  };
  std::map<std::string, DebugPublisher> debug_publishers_;

#if !NAV2_PYIF_LYRICAL_API
  // Jazzy and Humble transform the plan once, at setPlan: the plugin keeps it in the costmap's
  // frame as localisation moves (Lyrical's controller_server does that itself every cycle).
  FreshPlan plan_;
#endif
  // The last compute_velocity_commands got no reply in time: the host is likely gone, and
  // Nav2's reset() right after (while it aborts the goal) must not wait on it again. The reset
  // is then owed and sent before the next plan.
  bool host_silent_{false};
  bool reset_owed_{false};
};

}  // namespace nav2_pyif_bridge
