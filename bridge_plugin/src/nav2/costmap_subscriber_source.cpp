#include "nav2_pyif_bridge/costmap_subscriber_source.hpp"

#include "nav2_pyif_bridge/costmap_ros_source.hpp"

#include <stdexcept>
#include <utility>

namespace nav2_pyif_bridge
{

CostmapSubscriberSource::CostmapSubscriberSource(
  std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> subscriber, std::string frame_id)
: subscriber_(std::move(subscriber)), none_(frame_id), frame_id_(std::move(frame_id))
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
  std::unique_lock<nav2_costmap_2d::Costmap2D::mutex_t> lock(*costmap->getMutex());
  return client::read_costmap(costmap_view(*costmap, frame_id_), version_, known);
}

}  // namespace nav2_pyif_bridge
