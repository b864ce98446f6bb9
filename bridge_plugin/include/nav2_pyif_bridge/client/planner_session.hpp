// The global planner's call (the reference client's GlobalPlannerClient): create_plan, with
// Nav2's cancel checker polled while the plan is computed (PROTOCOL.md section 9).
#pragma once

#include <functional>
#include <optional>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class PlannerSession : public KindSession<PluginKind::GlobalPlanner>
{
public:
  using KindSession::KindSession;

  // The plan from `request`'s start, goal and (Lyrical) viapoints, in the costmap's global
  // frame; every value finite, else NoValidPathCouldBeFound. While waiting, `cancel_checker`
  // (when set) is polled about every 5 ms; once it returns true, one cancel_plan goes to
  // P/cancel and the wait goes on for the planner's answer (PlannerCancelled when it honours
  // it).
  protocol::Path create_plan(
    const protocol::CreatePlanRequest & request, const std::function<bool()> & cancel_checker = {});

  // cancel_plan requests sent so far.
  std::uint64_t cancels_sent() const;

private:
  void send_cancel(std::uint64_t target_seq);  // mutex() held

  std::uint64_t cancels_sent_{0};
};

}  // namespace nav2_pyif_bridge::client
