// The smoother's and the behaviours' costmap: a CostmapSubscriber (the costmap topic of
// smoother_server, of behavior_server), read under the costmap's lock; 0 x 0 until the
// subscription has received one. The subscriber does not say the costmap's frame: the caller
// gives it. The footprint is a FootprintSubscriber's (a behaviour's: the local costmap's
// published footprint, in the robot frame), or empty (robot radius 0) without one or before
// its first message.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "nav2_costmap_2d/costmap_subscriber.hpp"
#include "nav2_costmap_2d/footprint_subscriber.hpp"

#include "nav2_pyif_bridge/client/costmap_version.hpp"

namespace nav2_pyif_bridge
{

class CostmapSubscriberSource : public client::CostmapSource
{
public:
  CostmapSubscriberSource(
    std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> subscriber, std::string frame_id,
    std::shared_ptr<nav2_costmap_2d::FootprintSubscriber> footprint = nullptr);

  client::CostmapRead read(std::optional<std::uint64_t> known) override;

private:
  std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> subscriber_;
  std::shared_ptr<nav2_costmap_2d::FootprintSubscriber> footprint_;
  client::NoCostmap none_;  // its view until the first costmap arrives
  std::string frame_id_;
  std::mutex mutex_;
  client::CostmapVersion version_;
};

}  // namespace nav2_pyif_bridge
