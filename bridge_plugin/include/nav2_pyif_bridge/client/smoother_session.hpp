// The smoother's call (the reference client's SmootherClient): smooth, with the costmap
// (smoother_server's costmap subscription) sent when it changed.
#pragma once

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class SmootherSession : public KindSession<PluginKind::Smoother>
{
public:
  using KindSession::KindSession;

  // `path` in its own frame, `max_time` [s] -> the smoothed path (every value finite, else
  // FailedToSmoothPath) and whether the smoother finished (nav2_core's smooth() return). The
  // reply is awaited max_time and protocol::kSmoothGraceS more, or the plan timeout if longer.
  protocol::SmoothReply smooth(const protocol::Path & path, double max_time);
};

}  // namespace nav2_pyif_bridge::client
