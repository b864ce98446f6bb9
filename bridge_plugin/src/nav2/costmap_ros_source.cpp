#include "nav2_pyif_bridge/costmap_ros_source.hpp"

#include "nav2_pyif_bridge/plugin_bridge.hpp"
#include "nav2_pyif_bridge/ros_conversions.hpp"

#include <string>
#include <utility>
#include <vector>

namespace nav2_pyif_bridge
{
namespace
{

// The first layer with both inflation parameters (Nav2's InflationLayer, whatever its name in
// the YAML), read as the costmap node's parameters: the layer classes' getters differ between
// Nav2 versions, the parameter names do not.
protocol::Params inflation_parameters(nav2_costmap_2d::Costmap2DROS & costmap_ros)
{
  protocol::Params out;
  auto * layers = costmap_ros.getLayeredCostmap()->getPlugins();
  for (const auto & layer : *layers) {
    const std::string radius = layer->getName() + ".inflation_radius";
    const std::string factor = layer->getName() + ".cost_scaling_factor";
    if (!costmap_ros.has_parameter(radius) || !costmap_ros.has_parameter(factor)) {
      continue;
    }
    auto r = ros::to_wire(costmap_ros.get_parameter(radius).get_parameter_value());
    auto f = ros::to_wire(costmap_ros.get_parameter(factor).get_parameter_value());
    if (r && f) {
      out.set("inflation_radius", std::move(*r));
      out.set("cost_scaling_factor", std::move(*f));
      break;
    }
  }
  return out;
}

}  // namespace

client::CostmapView costmap_view(const nav2_costmap_2d::Costmap2D & costmap, std::string frame_id)
{
  client::CostmapView view;
  view.frame_id = std::move(frame_id);
  view.size_x = costmap.getSizeInCellsX();
  view.size_y = costmap.getSizeInCellsY();
  view.resolution = costmap.getResolution();
  view.origin_x = costmap.getOriginX();
  view.origin_y = costmap.getOriginY();
  view.data = costmap.getCharMap();
  return view;
}

CostmapRosSource::CostmapRosSource(std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
: costmap_ros_(std::move(costmap_ros))
{
}

client::CostmapRead CostmapRosSource::read(std::optional<std::uint64_t> known)
{
  std::lock_guard<std::mutex> tracker_lock(mutex_);
  const std::string frame = costmap_ros_->getGlobalFrameID();
  std::vector<double> footprint;
  for (const auto & point : costmap_ros_->getRobotFootprint()) {
    footprint.push_back(point.x);
    footprint.push_back(point.y);
  }
  nav2_costmap_2d::Costmap2D * costmap = costmap_ros_->getCostmap();
  std::unique_lock<nav2_costmap_2d::Costmap2D::mutex_t> lock(*costmap->getMutex());
  client::CostmapView view = costmap_view(*costmap, frame);
  view.footprint = std::move(footprint);
  view.robot_radius = costmap_ros_->getRobotRadius();  // every Nav2 from Humble 1.1.0
  return client::read_costmap(view, version_, known);
}

CostmapBinding bind_costmap(std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros)
{
  CostmapBinding binding;
  binding.global_frame = costmap_ros->getGlobalFrameID();
  binding.robot_base_frame = costmap_ros->getBaseFrameID();
  binding.transform_tolerance = costmap_ros->getTransformTolerance();
  binding.inflation = inflation_parameters(*costmap_ros);
  binding.source = std::make_unique<CostmapRosSource>(std::move(costmap_ros));
  return binding;
}

}  // namespace nav2_pyif_bridge
