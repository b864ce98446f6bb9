#include "nav2_pyif_bridge/py_plugin.hpp"

#include <stdexcept>
#include <utility>

#include "nav2_core/controller.hpp"
#include "nav2_core/global_planner.hpp"

#include "nav2_pyif_bridge/client/controller_session.hpp"
#include "nav2_pyif_bridge/client/planner_session.hpp"

namespace nav2_pyif_bridge
{

template<class Interface, class Session>
PyPlugin<Interface, Session>::~PyPlugin()
{
  session_.reset();
  bridge_.reset();
}

template<class Interface, class Session>
void PyPlugin<Interface, Session>::configure(
  const Nav2Node::WeakPtr & parent, std::string name,
  std::shared_ptr<TfBuffer> tf,
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
{
  auto node = parent.lock();
  if (!node) {
    throw std::runtime_error("nav2_pyif_bridge: " + name + ": unable to lock the node");
  }
  name_ = std::move(name);
  tf_ = std::move(tf);
  costmap_ros_ = std::move(costmap_ros);
  session_.reset();
  bridge_ = std::make_unique<PluginBridge>(node, name_, Session::kKind, costmap_ros_);
  session_ = std::make_unique<Session>(
    bridge_->session_config(), bridge_->transport(), bridge_->costmap(), bridge_->logger());
  bridge_->configure(*session_);
}

template<class Interface, class Session>
void PyPlugin<Interface, Session>::cleanup()
{
  if (bridge_ && session_) {
    bridge_->cleanup(*session_);
  }
  session_.reset();
  bridge_.reset();
}

template<class Interface, class Session>
void PyPlugin<Interface, Session>::activate()
{
  bridge_->lifecycle("activate", [this]() {session_->activate();});
}

template<class Interface, class Session>
void PyPlugin<Interface, Session>::deactivate()
{
  bridge_->lifecycle("deactivate", [this]() {session_->deactivate();});
}

template class PyPlugin<nav2_core::Controller, client::ControllerSession>;
template class PyPlugin<nav2_core::GlobalPlanner, client::PlannerSession>;

}  // namespace nav2_pyif_bridge
