#include "nav2_pyif_bridge/py_costmap_layer.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "nav2_costmap_2d/cost_values.hpp"
#include "pluginlib/class_list_macros.hpp"

namespace nav2_pyif_bridge
{
namespace proto = protocol;

namespace
{
#if !NAV2_PYIF_NAV2_MAX_KEEP_UNKNOWN
// What Nav2 1.3's CostmapLayer::updateWithMaxWithoutUnknownOverwrite does, which Humble's
// (1.1) lacks: the larger cost where both are known; the master's unknown cells stay unknown
// and the layer's unknown cells change nothing. `layer` is aligned with `master`.
void update_with_max_keeping_unknown(
  const unsigned char * layer, nav2_costmap_2d::Costmap2D & master, int min_i, int min_j,
  int max_i, int max_j)
{
  unsigned char * grid = master.getCharMap();
  const std::size_t span = master.getSizeInCellsX();
  for (int j = min_j; j < max_j; ++j) {
    for (int i = min_i; i < max_i; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * span + static_cast<std::size_t>(i);
      if (layer[k] != nav2_costmap_2d::NO_INFORMATION &&
        grid[k] != nav2_costmap_2d::NO_INFORMATION && grid[k] < layer[k])
      {
        grid[k] = layer[k];
      }
    }
  }
}
#endif
}  // namespace

void PyCostmapLayer::onInitialize()
{
  auto node = node_.lock();
  CostmapBinding none;  // the layer sees the master's geometry, never its costs
  none.global_frame = layered_costmap_->getGlobalFrameID();
  if (node && node->has_parameter("robot_base_frame")) {
    none.robot_base_frame = node->get_parameter("robot_base_frame").as_string();
  }
  none.source = std::make_unique<client::NoCostmap>(none.global_frame);
  plugin_.start(node_, name_, std::move(none));
  const std::string enabled = name_ + ".enabled";
  enabled_ = !node || !node->has_parameter(enabled) || node->get_parameter(enabled).as_bool();
  current_ = true;
  default_value_ = nav2_costmap_2d::NO_INFORMATION;
  matchSize();
}

void PyCostmapLayer::failed(const char * call, const client::CallError & error)
{
  current_ = false;
  if (!failing_) {
    RCLCPP_ERROR(
      plugin_.bridge().ros_logger(), "%s: %s failed, the costmap is not current until it works "
      "again: %s", name_.c_str(), call, error.log_text().c_str());
  }
  failing_ = true;
}

void PyCostmapLayer::updateBounds(
  double robot_x, double robot_y, double robot_yaw, double * min_x, double * min_y,
  double * max_x, double * max_y)
{
  if (!enabled_) {
    return;
  }
  proto::UpdateBoundsRequest request;
  request.robot_x = robot_x;
  request.robot_y = robot_y;
  request.robot_yaw = robot_yaw;
  request.min_x = *min_x;
  request.min_y = *min_y;
  request.max_x = *max_x;
  request.max_y = *max_y;
  try {
    const auto grown = plugin_.session().call(request);
    *min_x = std::min(*min_x, grown.min_x);
    *min_y = std::min(*min_y, grown.min_y);
    *max_x = std::max(*max_x, grown.max_x);
    *max_y = std::max(*max_y, grown.max_y);
  } catch (const client::CallError & error) {
    failed("update_bounds", error);
  }
}

void PyCostmapLayer::updateCosts(
  nav2_costmap_2d::Costmap2D & master_grid, int min_i, int min_j, int max_i, int max_j)
{
  if (!enabled_ || max_i <= min_i || max_j <= min_j) {
    return;
  }
  proto::UpdateCostsRequest request;
  request.min_i = min_i;
  request.min_j = min_j;
  request.max_i = max_i;
  request.max_j = max_j;
  request.origin_x = master_grid.getOriginX();
  request.origin_y = master_grid.getOriginY();
  request.resolution = master_grid.getResolution();
  proto::UpdateCostsReply reply;
  try {
    reply = plugin_.session().call(request);
  } catch (const client::CallError & error) {
    failed("update_costs", error);
    return;
  }
  // This layer's own grid is a scratch buffer aligned with the master (a rolling window moves
  // the master's origin between updates): the window goes there, then CostmapLayer's update
  // functions apply it.
  if (getOriginX() != master_grid.getOriginX() || getOriginY() != master_grid.getOriginY()) {
    updateOrigin(master_grid.getOriginX(), master_grid.getOriginY());
  }
  const int width = max_i - min_i;
  for (int j = min_j; j < max_j; ++j) {
    const auto row = reply.costs.begin() + static_cast<std::ptrdiff_t>(j - min_j) * width;
    std::copy(row, row + width, costmap_ + getIndex(min_i, j));
  }
  if (reply.combine == "overwrite") {
    updateWithOverwrite(master_grid, min_i, min_j, max_i, max_j);
  } else if (reply.combine == "true_overwrite") {
    updateWithTrueOverwrite(master_grid, min_i, min_j, max_i, max_j);
  } else if (reply.combine == "max_keep_unknown") {
#if NAV2_PYIF_NAV2_MAX_KEEP_UNKNOWN
    updateWithMaxWithoutUnknownOverwrite(master_grid, min_i, min_j, max_i, max_j);
#else
    update_with_max_keeping_unknown(costmap_, master_grid, min_i, min_j, max_i, max_j);
#endif
  } else {
    updateWithMax(master_grid, min_i, min_j, max_i, max_j);  // "max", and the host checks
  }
  if (failing_) {
    RCLCPP_INFO(plugin_.bridge().ros_logger(), "%s: the Python layer answers again", name_.c_str());
  }
  failing_ = false;
  current_ = true;
}

void PyCostmapLayer::matchSize()
{
  CostmapLayer::matchSize();
  nav2_costmap_2d::Costmap2D * master = layered_costmap_->getCostmap();
  proto::MatchSizeRequest request;
  request.size_x = master->getSizeInCellsX();
  request.size_y = master->getSizeInCellsY();
  request.resolution = master->getResolution();
  request.origin_x = master->getOriginX();
  request.origin_y = master->getOriginY();
  try {
    plugin_.session().call(request);
  } catch (const client::CallError & error) {
    failed("match_size", error);
  }
}

void PyCostmapLayer::reset()
{
  resetMaps();
  try {
    plugin_.session().call(proto::ResetRequest{});
  } catch (const client::CallError & error) {
    failed("reset", error);
  }
}

}  // namespace nav2_pyif_bridge

PLUGINLIB_EXPORT_CLASS(nav2_pyif_bridge::PyCostmapLayer, nav2_costmap_2d::Layer)
