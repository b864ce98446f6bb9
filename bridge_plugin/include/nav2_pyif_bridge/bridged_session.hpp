// A plugin's PluginBridge and session, started and stopped together, with Nav2's lifecycle
// forwarded: what every plugin class holds for its Nav2 lifetime.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "rclcpp_lifecycle/lifecycle_node.hpp"

#include "nav2_pyif_bridge/plugin_bridge.hpp"

namespace nav2_pyif_bridge
{

template<class Session>
class BridgedSession
{
public:
  BridgedSession() = default;
  ~BridgedSession() {stop();}
  BridgedSession(const BridgedSession &) = delete;
  BridgedSession & operator=(const BridgedSession &) = delete;

  // Parameters, transport, then the session: configured now, or deferred to the first call
  // when no host answers yet.
  void start(
    const rclcpp_lifecycle::LifecycleNode::WeakPtr & parent, const std::string & name,
    CostmapBinding costmap)
  {
    auto node = parent.lock();
    if (!node) {
      throw std::runtime_error("nav2_pyif_bridge: " + name + ": unable to lock the node");
    }
    stop();
    bridge_ = std::make_unique<PluginBridge>(node, name, Session::kKind, std::move(costmap));
    session_ = std::make_unique<Session>(
      bridge_->session_config(), bridge_->transport(), bridge_->costmap(), bridge_->logger());
    bridge_->configure(*session_);
  }

  // End the session (never throws).
  void stop() noexcept
  {
    if (bridge_ && session_) {
      bridge_->cleanup(*session_);
    }
    session_.reset();
    bridge_.reset();
  }

  // activate / deactivate: logged, never thrown (PluginBridge::lifecycle).
  void activate() {bridge_->lifecycle("activate", [this]() {session_->activate();});}
  void deactivate() {bridge_->lifecycle("deactivate", [this]() {session_->deactivate();});}

  bool started() const noexcept {return session_ != nullptr;}
  PluginBridge & bridge() {return *bridge_;}
  Session & session() {return *session_;}

private:
  // Destroyed in this order: the session uses the bridge's transport and costmap source.
  std::unique_ptr<PluginBridge> bridge_;
  std::unique_ptr<Session> session_;
};

}  // namespace nav2_pyif_bridge
