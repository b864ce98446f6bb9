// The costmap layer's calls (the reference client's CostmapLayerClient): bounds, the window's
// costs, the master grid's geometry, reset. Nav2 only initializes a layer: the plugin
// configures at onInitialize and cleans up when destroyed.
#pragma once

#include <cstdint>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class CostmapLayerSession : public KindSession<PluginKind::CostmapLayer>
{
public:
  using KindSession::KindSession;

  // The bounds (world metres) grown by the layer.
  protocol::UpdateBoundsReply update_bounds(const protocol::UpdateBoundsRequest & request);
  // The layer's costs for the window [min_i, max_i) x [min_j, max_j): checked to be exactly
  // that window (else a generic CallError).
  protocol::UpdateCostsReply update_costs(const protocol::UpdateCostsRequest & request);
  void match_size(const protocol::MatchSizeRequest & request);
  void reset();
};

}  // namespace nav2_pyif_bridge::client
