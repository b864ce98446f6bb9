// The session's costmap, read from Nav2's Costmap2DROS under the costmap's lock
// (PROTOCOL.md section 5); versions from client::CostmapVersion.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "nav2_costmap_2d/costmap_2d_ros.hpp"

#include "nav2_pyif_bridge/client/costmap_version.hpp"

namespace nav2_pyif_bridge
{

// The grid, its geometry and `frame_id` of a Nav2 costmap, as the session sends them (no
// footprint). The caller holds the costmap's mutex while the view is read: data points into it.
client::CostmapView costmap_view(const nav2_costmap_2d::Costmap2D & costmap, std::string frame_id);

class CostmapRosSource : public client::CostmapSource
{
public:
  explicit CostmapRosSource(std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros);

  client::CostmapRead read(std::optional<std::uint64_t> known) override;

private:
  std::shared_ptr<nav2_costmap_2d::Costmap2DROS> costmap_ros_;
  std::mutex mutex_;  // the version tracker: the controller and parameter threads may read
  client::CostmapVersion version_;
};

}  // namespace nav2_pyif_bridge
