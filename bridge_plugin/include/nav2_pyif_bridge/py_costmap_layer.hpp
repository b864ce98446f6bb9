// nav2_pyif_bridge::PyCostmapLayer: a nav2_costmap_2d layer whose costs come from a Python layer
// in a planner host, over Zenoh. Each costmap update: updateBounds asks the layer how far it
// reaches, updateCosts gets its uint8 window (only the window crosses the wire) and applies
// it to the master grid with CostmapLayer's own update functions, in the combine mode the
// layer names. A layer never throws into the costmap's update thread: a failure (no host, an
// error, a timeout) is logged, leaves the master grid untouched and marks the layer not
// current, so Nav2's servers wait for a current costmap and fail their action cleanly
// (controller_server: ControllerTimedOut) instead of driving on stale keep-out zones.
#pragma once

#include <string>

#include "nav2_costmap_2d/costmap_layer.hpp"

#include "nav2_pyif_bridge/bridged_session.hpp"
#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge
{

class PyCostmapLayer : public nav2_costmap_2d::CostmapLayer
{
public:
  void onInitialize() override;
  void updateBounds(
    double robot_x, double robot_y, double robot_yaw, double * min_x, double * min_y,
    double * max_x, double * max_y) override;
  void updateCosts(
    nav2_costmap_2d::Costmap2D & master_grid, int min_i, int min_j, int max_i,
    int max_j) override;
  void matchSize() override;
  void reset() override;
  bool isClearable() override {return false;}
  void activate() override {plugin_.activate();}
  void deactivate() override {plugin_.deactivate();}

private:
  // Log a failure (once per streak; the traceback when the host sent one) and mark the layer
  // not current.
  void failed(const char * call, const client::CallError & error);

  BridgedSession<client::CostmapLayerSession> plugin_;
  bool failing_{false};
};

}  // namespace nav2_pyif_bridge
