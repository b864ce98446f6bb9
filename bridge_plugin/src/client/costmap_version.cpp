#include "nav2_pyif_bridge/client/costmap_version.hpp"

#include <cstring>

namespace nav2_pyif_bridge::client
{
namespace
{

bool same_metadata(const protocol::Costmap & last, const CostmapView & view)
{
  return last.frame_id == view.frame_id && last.size_x == view.size_x &&
         last.size_y == view.size_y && last.resolution == view.resolution &&
         last.origin_x == view.origin_x && last.origin_y == view.origin_y &&
         last.footprint == view.footprint && last.robot_radius == view.robot_radius;
}

bool same_cells(const protocol::Costmap & last, const CostmapView & view)
{
  const std::size_t cells = view.cells();
  return last.data.size() == cells &&
         (cells == 0 || std::memcmp(last.data.data(), view.data, cells) == 0);
}

}  // namespace

std::uint64_t CostmapVersion::observe(const CostmapView & view)
{
  if (last_.version != 0 && same_metadata(last_, view) && same_cells(last_, view)) {
    return last_.version;
  }
  last_.version += 1;
  last_.frame_id = std::string(view.frame_id);
  last_.size_x = view.size_x;
  last_.size_y = view.size_y;
  last_.resolution = view.resolution;
  last_.origin_x = view.origin_x;
  last_.origin_y = view.origin_y;
  if (view.cells() == 0) {
    last_.data.clear();
  } else {
    last_.data.assign(view.data, view.data + view.cells());
  }
  last_.footprint = view.footprint;
  last_.robot_radius = view.robot_radius;
  return last_.version;
}

CostmapRead read_costmap(
  const CostmapView & view, CostmapVersion & tracker, std::optional<std::uint64_t> known)
{
  CostmapRead read;
  read.version = tracker.observe(view);
  if (known != read.version) {
    read.costmap = tracker.last();
  }
  return read;
}

CostmapView NoCostmap::view() const
{
  CostmapView view;
  view.frame_id = frame_id_;
  view.resolution = 1.0;  // any positive value: the host refuses a costmap of resolution 0
  return view;
}

CostmapRead NoCostmap::read(std::optional<std::uint64_t> known)
{
  return read_costmap(view(), version_, known);
}

}  // namespace nav2_pyif_bridge::client
