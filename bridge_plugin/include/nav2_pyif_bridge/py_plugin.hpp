// nav2_pyif_bridge::PyPlugin: the Nav2 lifecycle both plugins share. configure builds the
// PluginBridge (parameters, transport, costmap, logs) and a session of the plugin's kind;
// cleanup, activate and deactivate forward to them. PyController and PyGlobalPlanner derive
// from it and add their calls (their frames and messages).
#pragma once

#include <memory>
#include <string>

#include "nav2_costmap_2d/costmap_2d_ros.hpp"
#include "rclcpp_lifecycle/lifecycle_node.hpp"
#include "nav2_pyif_bridge/nav2_api.hpp"

#include "nav2_pyif_bridge/plugin_bridge.hpp"

namespace nav2_pyif_bridge
{

// Interface: nav2_core::Controller or nav2_core::GlobalPlanner; Session: the client session of
// that plugin type (its kKind names the type). Instantiated for both in py_plugin.cpp.
template<class Interface, class Session>
class PyPlugin : public Interface
{
public:
  PyPlugin() = default;
  ~PyPlugin() override;

  void configure(
    const Nav2Node::WeakPtr & parent, std::string name,
    std::shared_ptr<TfBuffer> tf,
    std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros) override;
  void cleanup() override;
  void activate() override;
  void deactivate() override;

protected:
  std::string name_;
  std::shared_ptr<TfBuffer> tf_;
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
  // Destroyed in this order: the session uses the bridge's transport and costmap source.
  std::unique_ptr<PluginBridge> bridge_;
  std::unique_ptr<Session> session_;
};

}  // namespace nav2_pyif_bridge
