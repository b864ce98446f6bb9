#include "rclcpp_topic_client.hpp"

#include <chrono>

namespace nav2_pyif_bench
{

using namespace std::chrono_literals;

namespace
{

// rclpy_node.py's QOS: reliable, depth 10, volatile.
rclcpp::QoS bench_qos()
{
  return rclcpp::QoS(10).reliable();
}

constexpr std::uint32_t kTagLimit = 999'999'999;  // nanosec stays a valid stamp

}  // namespace

RclcppTopicClient::RclcppTopicClient()
: node_(std::make_shared<rclcpp::Node>("pyif_bench_cpp_client"))
{
  odom_pub_ = node_->create_publisher<nav_msgs::msg::Odometry>("/pyif_bench/odom", bench_qos());
  cmd_sub_ = node_->create_subscription<geometry_msgs::msg::TwistStamped>(
    "/pyif_bench/cmd_vel", bench_qos(),
    [this](geometry_msgs::msg::TwistStamped::ConstSharedPtr cmd) {
      if (cmd->header.stamp.sec == 0 && cmd->header.stamp.nanosec == sent_tag_) {
        answered_ = true;
      }
    });
  executor_.add_node(node_);
  odom_.header.frame_id = "odom";
}

bool RclcppTopicClient::wait_ready(std::chrono::nanoseconds timeout)
{
  const auto deadline = BenchClock::now() + timeout;
  while (BenchClock::now() < deadline) {
    if (odom_pub_->get_subscription_count() > 0 && cmd_sub_->get_publisher_count() > 0 &&
      cycle(500ms))
    {
      return true;
    }
    executor_.spin_once(50ms);
  }
  return false;
}

std::optional<Sample> RclcppTopicClient::cycle(std::chrono::nanoseconds timeout)
{
  sent_tag_ = sent_tag_ >= kTagLimit ? 1 : sent_tag_ + 1;
  odom_.header.stamp.nanosec = sent_tag_;
  answered_ = false;
  const auto start = BenchClock::now();
  const auto deadline = start + timeout;
  odom_pub_->publish(odom_);
  while (!answered_) {
    const auto now = BenchClock::now();
    if (now >= deadline) {
      return std::nullopt;
    }
    executor_.spin_once(deadline - now);
  }
  return Sample{elapsed_ns(start)};
}

}  // namespace nav2_pyif_bench
