// How the units report what the user should read in Nav2's log. The plugins route it to
// RCLCPP_* on their node's logger; tests collect it.
#pragma once

#include <functional>
#include <string>

namespace nav2_pyif_bridge::client
{

enum class LogLevel {Debug, Info, Warn, Error};

// May be empty: nothing is logged.
using Logger = std::function<void (LogLevel, const std::string &)>;

inline void log(const Logger & logger, LogLevel level, const std::string & message)
{
  if (logger) {
    logger(level, message);
  }
}

}  // namespace nav2_pyif_bridge::client
