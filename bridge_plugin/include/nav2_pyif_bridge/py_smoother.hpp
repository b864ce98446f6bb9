// nav2_pyif_bridge::PySmoother: a nav2_core::Smoother (smoother_server) whose smoothing is done
// by a Python smoother in a planner host, over Zenoh. The path is smoothed in its own frame,
// as Nav2's smoothers do; the costmap is smoother_server's subscription.
#pragma once

#include <memory>
#include <string>

#include "nav2_core/smoother.hpp"
#include "nav_msgs/msg/path.hpp"
#include "rclcpp/rclcpp.hpp"

#include "nav2_pyif_bridge/bridged_session.hpp"
#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge
{

class PySmoother : public nav2_core::Smoother
{
public:
  void configure(
    const Nav2Node::WeakPtr & parent, std::string name,
    std::shared_ptr<TfBuffer> tf,
    std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> costmap_sub,
    std::shared_ptr<nav2_costmap_2d::FootprintSubscriber> footprint_sub) override;
  void cleanup() override {plugin_.stop();}
  void activate() override {plugin_.activate();}
  void deactivate() override {plugin_.deactivate();}
  // The smoothed path replaces `path`; false when the smoother stopped early. The reply is
  // awaited for max(max_time + 1 s, the plan_timeout parameter).
  bool smooth(nav_msgs::msg::Path & path, const rclcpp::Duration & max_time) override;

private:
  BridgedSession<client::SmootherSession> plugin_;
};

}  // namespace nav2_pyif_bridge
