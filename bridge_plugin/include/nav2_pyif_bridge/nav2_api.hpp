// Which Nav2 this package is built against, detected at build time from nav2_core's headers:
//   - NAV2_PYIF_JAZZY_API: nav2_core/controller_exceptions.hpp exists (Jazzy, Kilted, Lyrical):
//     the controller and planner exceptions, Controller::cancel/reset, the planner's cancel
//     checker. Humble has only nav2_core/exceptions.hpp (PlannerException).
//   - NAV2_PYIF_LYRICAL_API: nav2_core/path_handler.hpp exists (Lyrical, navigation2 1.5+):
//     controller_server transforms the plan itself (Controller::newPathReceived and the
//     five-argument computeVelocityCommands), the goal checker's isGoalXYReached and path
//     length tolerance, the planner's viapoints, and every plugin takes nav2::LifecycleNode and
//     nav2::TransformBuffer.
// CMake sets both from the same files (cmake/Nav2PyifApi.cmake); __has_include decides
// otherwise (tools that compile one file, testenv/compile_against_headers.py).
#pragma once

#include "nav2_pyif_bridge/client/error_mapping.hpp"

#ifndef NAV2_PYIF_JAZZY_API
#  if __has_include(<nav2_core/controller_exceptions.hpp>)
#    define NAV2_PYIF_JAZZY_API 1
#  else
#    define NAV2_PYIF_JAZZY_API 0
#  endif
#endif

#ifndef NAV2_PYIF_LYRICAL_API
#  if __has_include(<nav2_core/path_handler.hpp>)
#    define NAV2_PYIF_LYRICAL_API 1
#  else
#    define NAV2_PYIF_LYRICAL_API 0
#  endif
#endif

#if NAV2_PYIF_LYRICAL_API
#  include "nav2_ros_common/lifecycle_node.hpp"
#  include "nav2_ros_common/tf2_factories.hpp"
#else
#  include "rclcpp_lifecycle/lifecycle_node.hpp"
#  include "tf2_ros/buffer.h"
#endif

#if NAV2_PYIF_JAZZY_API
#  include "nav2_core/controller_exceptions.hpp"
#  include "nav2_core/planner_exceptions.hpp"
#else
#  include "nav2_core/exceptions.hpp"
#endif

namespace nav2_pyif_bridge
{

// The node and TF buffer types Nav2's plugin interfaces take. nav2::LifecycleNode derives from
// rclcpp_lifecycle::LifecycleNode and nav2::TransformBuffer is tf2_ros::Buffer, so everything
// past the plugin's entry points uses the rclcpp types on every distribution.
#if NAV2_PYIF_LYRICAL_API
using Nav2Node = nav2::LifecycleNode;
using TfBuffer = nav2::TransformBuffer;
#else
using Nav2Node = rclcpp_lifecycle::LifecycleNode;
using TfBuffer = tf2_ros::Buffer;
#endif

inline constexpr client::Nav2Api kNav2Api =
  NAV2_PYIF_JAZZY_API ? client::Nav2Api::Jazzy : client::Nav2Api::Humble;

// Throw the nav2_core exception class `kind` names on this distribution (Humble:
// PlannerException for everything), with `message`. `plugin` picks between nav2_core's two
// InvalidPath classes (the controller's and the smoother's).
[[noreturn]] void throw_nav2_exception(
  client::PluginKind plugin, client::ErrorKind kind, const std::string & message);

}  // namespace nav2_pyif_bridge
