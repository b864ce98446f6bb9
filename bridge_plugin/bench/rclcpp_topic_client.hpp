// The common workaround driven from C++: an rclcpp node publishes nav_msgs/Odometry to the
// separate rclpy node of benchmarks/nav2_pyif_bench/rclpy_node.py and waits for its
// geometry_msgs/TwistStamped, spinning its executor in the calling thread (as
// rclpy_client.py does: no background executor thread between the publish and the answer).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "geometry_msgs/msg/twist_stamped.hpp"
#include "nav_msgs/msg/odometry.hpp"
#include "rclcpp/rclcpp.hpp"

#include "sample.hpp"

namespace nav2_pyif_bench
{

class RclcppTopicClient
{
public:
  // rclcpp::init must have been called.
  RclcppTopicClient();

  // Both directions matched and one full exchange done (DDS discovery takes seconds).
  bool wait_ready(std::chrono::nanoseconds timeout);
  // Publish, then spin until the answer to this very message: std::nullopt on timeout.
  std::optional<Sample> cycle(std::chrono::nanoseconds timeout);

private:
  rclcpp::Node::SharedPtr node_;
  rclcpp::Publisher<nav_msgs::msg::Odometry>::SharedPtr odom_pub_;
  rclcpp::Subscription<geometry_msgs::msg::TwistStamped>::SharedPtr cmd_sub_;
  rclcpp::executors::SingleThreadedExecutor executor_;
  nav_msgs::msg::Odometry odom_;
  // The node echoes the header: the stamp's nanosec tags each request, so a late answer to an
  // earlier (timed-out) message cannot end a later cycle.
  std::uint32_t sent_tag_{0};
  bool answered_{false};
};

}  // namespace nav2_pyif_bench
