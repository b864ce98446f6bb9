#include "nav2_pyif_bridge/costmap_subscriber_source.hpp"

#include "nav2_pyif_bridge/costmap_ros_source.hpp"

#include <stdexcept>
#include <utility>
#include <vector>

namespace nav2_pyif_bridge
{

CostmapSubscriberSource::CostmapSubscriberSource(
  std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> subscriber, std::string frame_id,
  std::shared_ptr<nav2_costmap_2d::FootprintSubscriber> footprint)
: subscriber_(std::move(subscriber)), footprint_(std::move(footprint)), none_(frame_id),
  frame_id_(std::move(frame_id))
{
}

client::CostmapRead CostmapSubscriberSource::read(std::optional<std::uint64_t> known)
{
  std::lock_guard<std::mutex> tracker_lock(mutex_);
  std::shared_ptr<nav2_costmap_2d::Costmap2D> costmap;
  try {
    costmap = subscriber_ ? subscriber_->getCostmap() : nullptr;
  } catch (const std::runtime_error &) {
    costmap = nullptr;  // "Costmap is not available" before the first message
  }
  if (!costmap) {
    return client::read_costmap(none_.view(), version_, known);
  }
  std::vector<double> footprint;
  std::vector<geometry_msgs::msg::Point> points;
  std_msgs::msg::Header header;
  if (footprint_ && footprint_->getFootprintInRobotFrame(points, header)) {
    for (const auto & point : points) {
      footprint.push_back(point.x);
      footprint.push_back(point.y);
    }
  }
  std::unique_lock<nav2_costmap_2d::Costmap2D::mutex_t> lock(*costmap->getMutex());
  client::CostmapView view = costmap_view(*costmap, frame_id_);
  view.footprint = std::move(footprint);
  return client::read_costmap(view, version_, known);
}

}  // namespace nav2_pyif_bridge
