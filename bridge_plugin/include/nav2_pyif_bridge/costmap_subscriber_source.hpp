// The smoother's costmap: smoother_server's CostmapSubscriber (the costmap topic it names),
// read under the costmap's lock; 0 x 0 until the subscription has received one. The
// subscriber exposes neither the costmap's frame nor a footprint: the frame is the
// smoother's global frame parameter, the footprint is left empty (robot radius 0).
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "nav2_costmap_2d/costmap_subscriber.hpp"

#include "nav2_pyif_bridge/client/costmap_version.hpp"

namespace nav2_pyif_bridge
{

class CostmapSubscriberSource : public client::CostmapSource
{
public:
  CostmapSubscriberSource(
    std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> subscriber, std::string frame_id);

  client::CostmapRead read(std::optional<std::uint64_t> known) override;

private:
  std::shared_ptr<nav2_costmap_2d::CostmapSubscriber> subscriber_;
  client::NoCostmap none_;  // its view until the first costmap arrives
  std::string frame_id_;
  std::mutex mutex_;
  client::CostmapVersion version_;
};

}  // namespace nav2_pyif_bridge
