// What both Nav2 plugins share, so each plugin class only forwards: the YAML parameters
// (client/settings.hpp), the local planner host (client/local_host.hpp), the Zenoh transport,
// the costmap source, `ros2 param set` forwarding, and turning a CallError into the nav2_core
// exception with the Python traceback in the log.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "nav2_costmap_2d/costmap_2d_ros.hpp"
#include "rclcpp/rclcpp.hpp"
#include "rclcpp_lifecycle/lifecycle_node.hpp"

#include "nav2_pyif_bridge/client/local_host.hpp"
#include "nav2_pyif_bridge/client/plugin_session.hpp"
#include "nav2_pyif_bridge/client/settings.hpp"
#include "nav2_pyif_bridge/costmap_ros_source.hpp"
#include "nav2_pyif_bridge/nav2_api.hpp"
#include "nav2_pyif_bridge/zenoh_transport.hpp"

namespace nav2_pyif_bridge
{

// Where a plugin's costmap and frames come from: Costmap2DROS (controller, planner, goal
// checker), the smoother's costmap subscription, or nothing (progress checker).
struct CostmapBinding
{
  std::unique_ptr<client::CostmapSource> source;
  std::string global_frame;
  std::string robot_base_frame;
  double transform_tolerance{0.1};  // [s]
  // the inflation layer's inflation_radius and cost_scaling_factor, for configure's
  // nav2_params (empty: the costmap has no inflation layer)
  protocol::Params inflation;
};

// The binding of a Costmap2DROS: its costmap, frames and transform tolerance.
CostmapBinding bind_costmap(std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros);

class PluginBridge
{
public:
  // Reads and declares the plugin's parameters, starts the local host when asked, opens the
  // transport. Throws the nav2_core exception of a plugin that cannot be configured
  // (InvalidController / InvalidPlanner / InvalidSmoother; Humble: PlannerException) for bad
  // parameters or a local host that cannot start.
  PluginBridge(
    const rclcpp_lifecycle::LifecycleNode::SharedPtr & node, const std::string & name,
    client::PluginKind kind, CostmapBinding costmap);
  ~PluginBridge();
  PluginBridge(const PluginBridge &) = delete;
  PluginBridge & operator=(const PluginBridge &) = delete;

  // The parts a session is made of (the plugin creates its typed session with them).
  const client::SessionConfig & session_config() const noexcept {return config_;}
  client::Transport & transport() {return *transport_;}
  client::CostmapSource & costmap() {return *costmap_source_;}
  client::Logger logger() const;

  // Wait for a host (wait_for_host), configure the session or defer it when no host answers;
  // declare the parameters the planner declared; start forwarding `ros2 param set`.
  void configure(client::PluginSession & session);
  // Stop forwarding parameters, end the session (never throws), stop the local host.
  void cleanup(client::PluginSession & session) noexcept;

  // Log the traceback (when the host sent one), then throw the nav2_core exception.
  [[noreturn]] void fail(const client::CallError & error) const;
  // Run `call`, turning a CallError into the nav2_core exception.
  template<class F>
  decltype(auto) forward(F && call) const
  {
    try {
      return call();
    } catch (const client::CallError & error) {
      fail(error);
    }
  }

  // activate / deactivate: a planner that fails them (or no host) is logged, never thrown, so
  // Nav2's lifecycle goes on (a thrown transition would leave the server in its error state).
  template<class F>
  void lifecycle(const char * transition, F && call) const
  {
    try {
      call();
    } catch (const client::CallError & error) {
      RCLCPP_ERROR(
        logger_, "%s: %s failed: %s", config_.name.c_str(), transition, error.log_text().c_str());
    }
  }

  const rclcpp::Logger & ros_logger() const noexcept {return logger_;}
  rclcpp::Clock::SharedPtr clock() const noexcept {return clock_;}
  const std::vector<client::InputSpec> & inputs() const noexcept {return inputs_;}
  double transform_tolerance() const noexcept {return transform_tolerance_;}

private:
  rcl_interfaces::msg::SetParametersResult on_parameters(
    const std::vector<rclcpp::Parameter> & parameters);
  // Stop the local host once the node is finalized (`ros2 lifecycle set <node> shutdown`).
  void stop_local_host_when_finalized(rclcpp_lifecycle::LifecycleNode & node);
  void declare_planner_parameters(const protocol::Params & declared);

  rclcpp_lifecycle::LifecycleNode::WeakPtr node_;
  rclcpp::Logger logger_;
  rclcpp::Clock::SharedPtr clock_;
  double transform_tolerance_{0.1};

  client::BridgeParameters settings_;
  std::vector<client::InputSpec> inputs_;
  // The session's: the plugin's name, node and frames, the forwarded parameters, the key, and
  // configure's nav2_params (Nav2's own, outside the plugin's namespace)
  client::SessionConfig config_;
  std::mutex local_host_mutex_;  // the finalized check stops it from the node's executor
  std::unique_ptr<client::LocalHost> local_host_;
  rclcpp::TimerBase::SharedPtr finalized_check_;
  std::unique_ptr<ZenohTransport> transport_;
  std::unique_ptr<client::CostmapSource> costmap_source_;

  client::PluginSession * session_{nullptr};
  rclcpp::node_interfaces::OnSetParametersCallbackHandle::SharedPtr parameter_callback_;
  std::atomic<bool> declaring_{false};
};

}  // namespace nav2_pyif_bridge
