#include "nav2_pyif_bridge/plugin_bridge.hpp"

#include <chrono>
#include <stdexcept>
#include <utility>
#include <vector>

// rcutils_log and its logger check, through rclcpp's logging (its macros are built on them):
// the package's key for them is rclcpp's
#include "rclcpp/logging.hpp"

#include "nav2_pyif_bridge/client/carried_cycle.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"

namespace nav2_pyif_bridge
{
namespace proto = protocol;
using client::CallError;
using client::LogLevel;

namespace
{

rcl_interfaces::msg::ParameterDescriptor dynamically_typed()
{
  rcl_interfaces::msg::ParameterDescriptor descriptor;
  descriptor.dynamic_typing = true;  // the planner host judges the types (an int for a float)
  return descriptor;
}

// Every parameter under `name.`, prefix stripped: those given to the node (the params YAML,
// launch arguments), declared here, and those declared already (a configure after cleanup
// sees the values `ros2 param set` left).
proto::Params read_parameters(rclcpp_lifecycle::LifecycleNode & node, const std::string & name)
{
  const auto overrides = node.get_node_parameters_interface()->get_parameter_overrides();
  for (const auto & [full_name, value] : overrides) {
    if (client::plugin_parameter_name(full_name, name) && !node.has_parameter(full_name)) {
      node.declare_parameter(full_name, value, dynamically_typed());
    }
  }
  proto::Params out;
  const auto listed = node.list_parameters({name}, 0);
  for (const auto & full_name : listed.names) {
    const auto stripped = client::plugin_parameter_name(full_name, name);
    if (!stripped) {
      continue;
    }
    if (auto value = ros::to_wire(node.get_parameter(full_name).get_parameter_value())) {
      out.set(*stripped, std::move(*value));
    }
  }
  return out;
}

}  // namespace

PluginBridge::PluginBridge(
  const rclcpp_lifecycle::LifecycleNode::SharedPtr & node, const std::string & name,
  client::PluginKind kind, CostmapBinding costmap)
: node_(node), logger_(node->get_logger().get_child(name)), clock_(node->get_clock()),
  transform_tolerance_(costmap.transform_tolerance), costmap_source_(std::move(costmap.source))
{
  config_.kind = kind;
  config_.name = name;
  config_.node = node->get_name();
  config_.nav2_params = std::move(costmap.inflation);
  config_.global_frame = std::move(costmap.global_frame);
  config_.robot_base_frame = std::move(costmap.robot_base_frame);
  // The controller server's rate: a controller's control period (an MPC's time step).
  if (node->has_parameter("controller_frequency")) {
    if (auto hz = ros::to_wire(node->get_parameter("controller_frequency").get_parameter_value())) {
      config_.nav2_params.set("controller_frequency", std::move(*hz));
    }
  }
  try {
    client::PluginParameters parameters = client::split_parameters(read_parameters(*node, name));
    settings_ = std::move(parameters.settings);
    inputs_ = std::move(parameters.inputs);
    config_.params = std::move(parameters.forwarded);
    config_.timeouts = settings_.timeouts;
    config_.key_prefix =
      settings_.key.empty() ? client::local_host_key(config_.node, name) : settings_.key;
    // (Humble's LifecycleNode has no get_fully_qualified_name; its node base interface has)
    const std::string server = node->get_node_base_interface()->get_fully_qualified_name();
    ZenohOptions zenoh{settings_.zenoh_config, settings_.zenoh_connect, server};
    if (client::starts_local_host(settings_)) {
      local_host_ = std::make_unique<client::LocalHost>(settings_, config_.key_prefix, logger());
      zenoh = ZenohOptions{"", {local_host_->endpoint()}, server};
      stop_local_host_when_finalized(*node);
    }
    transport_ =
      std::make_unique<ZenohTransport>(zenoh, client::KeySpace(config_.key_prefix), logger());
  } catch (const std::exception & error) {
    RCLCPP_FATAL(logger_, "%s: %s", config_.name.c_str(), error.what());
    throw_nav2_exception(
      config_.kind, client::for_api(client::invalid_error(config_.kind), kNav2Api),
      config_.name + ": " + error.what());
  }
  RCLCPP_INFO(
    logger_, "%s: Python planner on Zenoh key %s (%s, %s%s)", config_.name.c_str(),
    config_.key_prefix.c_str(), zenoh_backend(), transport_->where().c_str(),
    local_host_ ? ", local planner-host started by this plugin" : "");
}

PluginBridge::~PluginBridge()
{
  parameter_callback_.reset();
  finalized_check_.reset();
  transport_.reset();
  const std::lock_guard<std::mutex> lock(local_host_mutex_);
  local_host_.reset();  // stops the process
}

void PluginBridge::stop_local_host_when_finalized(rclcpp_lifecycle::LifecycleNode & node)
{
  // A shutdown from active or inactive finalizes the node without cleaning its plugins up
  // (Nav2's servers do nothing in on_shutdown), and in a component container the node, this
  // plugin and its host live on. No hook tells a plugin of it: the node's state, read twice a
  // second on the node's own executor, does.
  finalized_check_ = node.create_wall_timer(
    std::chrono::milliseconds(500), [this]() {
      auto locked = node_.lock();
      if (!locked || locked->get_current_state().label() != "finalized") {
        return;
      }
      finalized_check_->cancel();
      const std::lock_guard<std::mutex> lock(local_host_mutex_);
      if (local_host_) {
        RCLCPP_INFO(
          logger_, "%s: node finalized: stopping its local planner host", config_.name.c_str());
        local_host_->stop();
      }
    });
}

client::Logger PluginBridge::logger() const
{
  return [logger = logger_](LogLevel level, const std::string & text) {
           // client::LogLevel's order: Debug, Info, Warn, Error
           static constexpr int kSeverity[] = {
             RCUTILS_LOG_SEVERITY_DEBUG, RCUTILS_LOG_SEVERITY_INFO, RCUTILS_LOG_SEVERITY_WARN,
             RCUTILS_LOG_SEVERITY_ERROR};
           // rcutils_log itself: the macros with a run-time severity differ by release
           // (RCUTILS_LOG_COND_NAMED up to Kilted, RCUTILS_LOG_NAMED in Lyrical)
           const int severity = kSeverity[static_cast<int>(level)];
           RCUTILS_LOGGING_AUTOINIT;
           if (rcutils_logging_logger_is_enabled_for(logger.get_name(), severity)) {
             static const rcutils_log_location_t location = {__func__, __FILE__, __LINE__};
             rcutils_log(&location, severity, logger.get_name(), "%s", text.c_str());
           }
         };
}

void PluginBridge::configure(client::PluginSession & session)
{
  session_ = &session;
  auto node = node_.lock();
  if (node && protocol::in_carried_cycle(config_.kind)) {
    // (through the node base interface: Humble's LifecycleNode has no get_fully_qualified_name)
    session.join(
      client::CarriedCycle::of(node->get_node_base_interface()->get_fully_qualified_name()));
  }
  const auto wait = client::host_wait(settings_);
  if (!session.wait_for_host(wait)) {
    RCLCPP_WARN(
      logger_, "%s: no planner host on %s after %.1f s; configure deferred to the first call "
      "(start one: planner-host --key %s ...)", config_.name.c_str(), config_.key_prefix.c_str(),
      std::chrono::duration<double>(wait).count(), config_.key_prefix.c_str());
    session.defer_configure();
  } else {
    try {
      const proto::Params declared = session.configure();
      const client::SessionState state = session.state();
      RCLCPP_INFO(
        logger_, "%s: configured on host %s (session %s)%s%s", config_.name.c_str(),
        state.last_host.c_str(), session.sid().substr(0, 8).c_str(),
        state.served.empty() ? "" : ", serving ", state.served.c_str());
      declare_planner_parameters(declared);
    } catch (const CallError & error) {
      if (!error.unreachable()) {
        fail(error);
      }
      RCLCPP_WARN(
        logger_, "%s: %s; configure deferred to the first call", config_.name.c_str(),
        error.what());
      session.defer_configure();
    }
  }
  if (node) {
    parameter_callback_ = node->add_on_set_parameters_callback(
      [this](const std::vector<rclcpp::Parameter> & parameters) {
        return on_parameters(parameters);
      });
  }
}

void PluginBridge::cleanup(client::PluginSession & session) noexcept
{
  parameter_callback_.reset();
  try {
    session.cleanup();
  } catch (const std::exception & error) {
    RCLCPP_WARN(logger_, "%s: cleanup: %s", config_.name.c_str(), error.what());
  }
  session_ = nullptr;
}

void PluginBridge::declare_planner_parameters(const proto::Params & declared)
{
  auto node = node_.lock();
  if (!node) {
    return;
  }
  declaring_ = true;
  for (const auto & [name, value] : declared) {
    const std::string full_name = config_.name + "." + name;
    try {
      if (!node->has_parameter(full_name)) {
        node->declare_parameter(full_name, ros::to_ros(value), dynamically_typed());
      }
    } catch (const std::exception & error) {
      RCLCPP_WARN(logger_, "cannot declare %s: %s", full_name.c_str(), error.what());
    }
  }
  declaring_ = false;
}

rcl_interfaces::msg::SetParametersResult PluginBridge::on_parameters(
  const std::vector<rclcpp::Parameter> & parameters)
{
  rcl_interfaces::msg::SetParametersResult result;
  result.successful = true;
  if (declaring_ || session_ == nullptr) {
    return result;
  }
  proto::Params changes;
  client::BridgeParameters settings = settings_;
  settings.timeouts = session_->timeouts();
  std::string problems;
  auto problem = [&problems](const std::string & text) {
      problems += (problems.empty() ? "" : "; ") + text;
    };
  for (const auto & parameter : parameters) {
    const auto name = client::plugin_parameter_name(parameter.get_name(), config_.name);
    if (!name) {
      continue;
    }
    const auto value = ros::to_wire(parameter.get_parameter_value());
    if (!value) {
      problem(*name + ": cannot be unset");
    } else if (!client::is_bridge_parameter(*name)) {
      changes.set(*name, *value);
    } else if (!client::is_live_parameter(*name)) {
      problem(*name + " is read at configure: cleanup and configure the node to change it");
    } else {
      try {
        client::set_bridge_parameter(settings, *name, *value);
      } catch (const std::invalid_argument & error) {
        problem(error.what());
      }
    }
  }
  if (!problems.empty()) {
    result.successful = false;
    result.reason = problems;
    return result;
  }
  if (!changes.empty()) {
    try {
      const proto::StringMap rejected = session_->set_parameters(changes);
      for (const auto & [name, reason] : rejected) {
        problem(name + ": " + reason);
      }
    } catch (const CallError & error) {
      problem(error.what());
    }
  }
  if (!problems.empty()) {
    result.successful = false;
    result.reason = "the planner refused: " + problems;
    return result;
  }
  settings_ = std::move(settings);
  session_->set_timeouts(settings_.timeouts);
  return result;
}

void PluginBridge::fail(const CallError & error) const
{
  if (!error.remote().traceback.empty()) {
    RCLCPP_ERROR(logger_, "%s: %s", config_.name.c_str(), error.log_text().c_str());
  } else {
    RCLCPP_DEBUG(logger_, "%s: %s", config_.name.c_str(), error.what());
  }
  throw_nav2_exception(config_.kind, client::for_api(error.kind(), kNav2Api), error.what());
}

}  // namespace nav2_pyif_bridge
