// The costmap's version counter (PROTOCOL.md section 5): the plugin sends the costmap only
// when its version differs from the one this session last delivered.
//
// How a change is detected: Nav2's Costmap2D keeps no update counter (Humble to Kilted), and
// a cheap hash can collide, so CostmapVersion keeps a copy of the last costmap it saw and
// compares exactly: metadata field by field, the cells with memcmp (about 1 ms per 10 MB of
// cells; a local costmap of 3 m x 3 m at 5 cm is 3.6 kB). Any difference in the cells, size,
// resolution, origin, frame, footprint or robot radius bumps the version. The copy is also
// what is sent, so reading the costmap copies its cells only when they changed. A rolling
// local costmap changes with every update while the robot moves, and then travels with every
// control cycle; a static global costmap travels once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::client
{

// A costmap as Nav2 holds it, borrowed for the time of one read (under the costmap's lock).
struct CostmapView
{
  std::string_view frame_id;
  std::uint32_t size_x{0};
  std::uint32_t size_y{0};
  double resolution{0.0};
  double origin_x{0.0};
  double origin_y{0.0};
  const std::uint8_t * data{nullptr};  // size_x * size_y costs, index my * size_x + mx
  std::vector<double> footprint;       // K x 2: x, y [m] in the robot frame
  double robot_radius{0.0};

  std::size_t cells() const noexcept {return std::size_t{size_x} * size_y;}
};

class CostmapVersion
{
public:
  // Compare `view` with the last costmap observed; bump the version when anything differs.
  // Returns the current version: 1 for the first costmap, +1 at each change.
  std::uint64_t observe(const CostmapView & view);

  std::uint64_t version() const noexcept {return last_.version;}
  // The last costmap observed, as the wire carries it (version included).
  const protocol::Costmap & last() const noexcept {return last_;}

private:
  protocol::Costmap last_;
};

struct CostmapRead
{
  std::uint64_t version{0};
  // A copy of the costmap, unless the reader said it already has this version.
  std::optional<protocol::Costmap> costmap;
};

// Observe `view` in `tracker`; copy it unless `known` is the current version.
CostmapRead read_costmap(
  const CostmapView & view, CostmapVersion & tracker, std::optional<std::uint64_t> known);

// Where a session reads its costmap: Costmap2DROS in the plugins (under the costmap's lock),
// a plain grid in the tests.
class CostmapSource
{
public:
  virtual ~CostmapSource() = default;
  // The current version, and a copy of the costmap unless `known` is that version.
  virtual CostmapRead read(std::optional<std::uint64_t> known) = 0;
};

}  // namespace nav2_pyif_bridge::client

namespace nav2_pyif_bridge::client
{

// The costmap of a plugin Nav2 gives none (a progress checker), or none yet (a smoother before
// its costmap subscription received one): 0 x 0 cells, resolution 1 m (PROTOCOL.md section 14).
class NoCostmap : public CostmapSource
{
public:
  explicit NoCostmap(std::string frame_id = {}) : frame_id_(std::move(frame_id)) {}
  CostmapRead read(std::optional<std::uint64_t> known) override;
  // The view read() reports: what a source without a costmap yet observes.
  CostmapView view() const;

private:
  std::string frame_id_;
  CostmapVersion version_;
};

}  // namespace nav2_pyif_bridge::client
